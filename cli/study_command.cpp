// cli/study_command.cpp — `softmol study MOLECULE -o DIR`: what each accuracy knob costs in time
// and in error (cli/study.h runs the sweep). Loads the molecule as `softmol render` draws it by
// default (spacefill, no water), frames --views views turning about the vertical axis, sweeps the
// knobs, and writes into DIR one CSV per method, summary.md and the plots that
// scripts/study_plot.py draws from the CSVs (when python3 with matplotlib is there). Prints a
// progress line per point on stderr and a one-screen table of each method's front on stdout.
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>

#include <CLI/CLI.hpp>
#include <tbb/global_control.h>

#include "cli/commands.h"
#include "cli/load_molecule.h"
#include "cli/parse.h"
#include "cli/study.h"
#include "io/atomic_file.h"
#include "io/error.h"
#include "raster/representation.h"
#include "raster/simd_target.h"
#include "scene/layers.h"

extern char** environ;

namespace softmol::cli {
namespace {

constexpr const char* kStudyHelp =
    "Each method's knobs are swept one at a time around the shipped defaults, plus the product of "
    "the two that interact (baked: ao-patch x ao-map; cone: cones x ao-grid; shadows: pcf-samples x "
    "pcf-pretest). Times are the frame's own per-pass profile (median of --repeats); errors are "
    "against a ground truth of the same frames: the ray-traced reference AO (baked, cone), 256 "
    "samples a pixel on silhouette pixels (ssaa), 256 PCF taps on an 8192^2 map (shadows), the "
    "double-precision reference ray caster with the molecule also moved 1e4 and 1e5 A from the origin "
    "(setup-precision).\n"
    "DIR gets METHOD.csv per method, summary.md and METHOD.png (error against cost, the Pareto "
    "front joined, the shipped default circled; scripts/study_plot.py, python3-matplotlib). "
    "A bad option or molecule writes nothing.";

std::vector<std::string> SplitCommas(std::string_view text) {
  std::vector<std::string> parts;
  for (size_t start = 0; start <= text.size();) {
    size_t comma = text.find(',', start);
    if (comma == std::string_view::npos) comma = text.size();
    parts.emplace_back(io::TrimBlanks(text.substr(start, comma - start)));
    start = comma + 1;
  }
  return parts;
}

void CheckKnobs(std::string_view text, const io::SourceLocation& where) {
  (void)study::SelectKnobs(study::DefaultPlans(), SplitCommas(text), where);
}

// The drawn scene and its cameras: view k turned k·360/N degrees about the image's vertical
// axis from the oriented default camera (render's --rotate 0,k·360/N,0).
struct StudyScene {
  LoadedMolecule loaded;
  raster::Representation drawn;
  std::vector<raster::Camera> views;
};

StudyScene LoadScene(const StudyArgs& a) {
  StudyScene s;
  const scene::SceneLayers layers;
  s.loaded = LoadMolecule(a.molecule, a.assembly, "", scene::NeedsBonds(layers));
  const scene::ResolvedLooks looks = scene::ResolveLooks(s.loaded.molecule, layers);
  s.drawn = raster::BuildRepresentation(s.loaded.molecule, looks.looks, raster::RepresentationOptions{});
  if (s.drawn.scene.size() == 0) throw io::InputError({a.molecule}, "nothing to draw (only water?)");
  const ImageSize size = ParseSize(a.size, "--size");
  for (int k = 0; k < a.views; ++k) {
    raster::Camera cam = raster::OrientedCamera(s.drawn.scene, size.width, size.height);
    if (k > 0) raster::ApplyRotation(cam, {0.0, 360.0 * k / a.views, 0.0}, s.drawn.scene.Bounds().center);
    raster::FitNearFar(cam, s.drawn.scene);
    s.views.push_back(cam);
  }
  return s;
}

// "[#####     ] 12/40 baked-ao ao-map=4096" redrawn in place on a terminal, a line each otherwise.
void Progress(size_t done, size_t total, const std::string& method, const std::string& label) {
  const bool tty = isatty(STDERR_FILENO);
  const int width = 20, filled = total ? int(width * done / total) : width;
  if (tty)
    std::fprintf(stderr, "\r[%.*s%*s] %zu/%zu %s %-40.40s", filled, "####################", width - filled, "", done,
                 total, method.c_str(), label.c_str());
  else
    std::fprintf(stderr, "study: %zu/%zu %s %s\n", done, total, method.c_str(), label.c_str());
  if (tty && done == total) std::fprintf(stderr, "\n");
}

void WriteText(const std::filesystem::path& path, const std::string& text) {
  io::TemporaryFile file(path.string());
  file.Write(text.data(), text.size());
  file.Commit();
}

const study::Row* DefaultRow(const study::MethodResult& r) {
  for (const study::Row& row : r.rows)
    if (row.point.isDefault) return &row;
  return nullptr;
}

std::string Format(const char* format, double v) {
  char text[64];
  std::snprintf(text, sizeof text, format, v);
  return text;
}

std::string SummaryHeader(const StudyArgs& a, const StudyScene& s) {
  const raster::PrimitiveScene& sc = s.drawn.scene;
  return "# softmol study: " + std::filesystem::path(a.molecule).filename().string() + "\n\n" +
         std::to_string(s.loaded.molecule.atomCount()) + " atoms drawn as " + std::to_string(sc.spheres.size()) +
         " spheres and " + std::to_string(sc.cylinders.size()) + " cylinders (spacefill); " + a.size + ", " +
         std::to_string(a.views) + " view(s) turning about the vertical axis; times are the median of " +
         std::to_string(a.repeats) + " repetition(s) per view, on " +
         (a.threads > 0 ? std::to_string(a.threads) + " thread(s)" : std::string("every core")) + ", SIMD target " +
         raster::ActiveSimdTarget() + ". Cost = setup (the AO bake, paid once per structure) + frame (the "
         "method's own passes per frame; the whole frame for SSAA). The front is the Pareto front of "
         "(cost, error).\n";
}

std::string MethodSummary(const study::MethodResult& r) {
  std::string md = "\n## " + r.plan.name + "\n\nError: " + r.errorName + ". Ground truth: " + r.reference +
                   ".\n\nShipped defaults (`softmol render`):";
  for (size_t k = 0; k < r.plan.knobs.size(); ++k) md += " --" + r.plan.knobs[k].name + " " + r.defaults[k];
  md += ".\n\n";
  md += "| point | setup ms | frame ms | error | p95 | front |\n|---|---:|---:|---:|---:|:-:|\n";
  for (const study::Row& row : r.rows)
    md += "| " + row.label + (row.point.isDefault ? " (shipped)" : "") + " | " + Format("%.2f", row.setupMs) + " | " +
          Format("%.3f", row.frameMs) + " | " + Format("%.5f", row.error.mean) + " | " + Format("%.5f", row.errorP95) +
          " | " + (row.front ? "yes" : "") + " |\n";
  if (const study::Row* d = DefaultRow(r))
    md += "\nShipped default: error " + Format("%.5f", d->error.mean) + ", " +
          (d->front ? "on the front." : "NOT on the front (another point is both cheaper and more accurate).") + "\n";
  if (!r.detail.empty()) md += "\n" + r.detail;
  md += "\n![" + r.plan.name + "](" + r.plan.name + ".png)\n";
  return md;
}

// The front and the shipped default of each method, as a table that fits a screen.
void PrintTable(const std::vector<study::MethodResult>& results) {
  for (const study::MethodResult& r : results) {
    std::printf("%s: %s\n", r.plan.name.c_str(), r.errorName.c_str());
    std::printf("  %-34s %10s %10s %9s %9s\n", "point (front, * = shipped)", "setup ms", "frame ms", "error", "p95");
    for (const study::Row& row : r.rows)
      if (row.front || row.point.isDefault)
        std::printf("  %-34.34s %10.2f %10.3f %9.5f %9.5f%s\n", (row.label + (row.point.isDefault ? " *" : "")).c_str(),
                    row.setupMs, row.frameMs, row.error.mean, row.errorP95, row.front ? "" : "  (off the front)");
    if (!r.referenceReached) std::printf("  warning: %s\n", r.reference.c_str());
  }
}

std::string PlotScript() {
  if (const char* env = std::getenv("SOFTMOL_STUDY_PLOT"); env && *env) return env;
  return SOFTMOL_STUDY_PLOT;
}

// python3 SCRIPT DIR; a missing python3 or matplotlib leaves the CSVs and says so. Debian's
// interpreter first: python3-matplotlib (scripts/setup.sh) is installed for it, and a python3
// earlier on the PATH (pyenv, a venv) may lack it.
void RunPlotScript(const std::filesystem::path& dir) {
  const std::string script = PlotScript(), folder = dir.string();
  if (!std::filesystem::exists(script)) {
    std::fprintf(stderr, "softmol: warning: no plots: %s is missing\n", script.c_str());
    return;
  }
  std::string python = std::filesystem::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
  char* argv[] = {python.data(), const_cast<char*>(script.c_str()), const_cast<char*>(folder.c_str()), nullptr};
  pid_t pid = 0;
  int status = 0;
  if (posix_spawnp(&pid, python.c_str(), nullptr, nullptr, argv, environ) != 0 || waitpid(pid, &status, 0) != pid ||
      !WIFEXITED(status) || WEXITSTATUS(status) != 0)
    std::fprintf(stderr, "softmol: warning: no plots: %s failed (needs python3-matplotlib)\n", script.c_str());
}

void WriteOutputs(const StudyArgs& a, const StudyScene& s, const std::vector<study::MethodResult>& results) {
  const std::filesystem::path dir = a.output;
  std::string md = SummaryHeader(a, s);
  for (const study::MethodResult& r : results) {
    WriteText(dir / (r.plan.name + ".csv"), study::CsvText(r));
    md += MethodSummary(r);
  }
  WriteText(dir / "summary.md", md);
  RunPlotScript(dir);
}

void MakeOutputFolder(const std::string& dir) {
  std::error_code error;
  std::filesystem::create_directories(dir, error);
  if (error || !std::filesystem::is_directory(dir))
    throw io::InputError({"-o"}, "cannot make the folder '" + dir + "': " + (error ? error.message() : "not a folder"));
}

}  // namespace

io::ParamTable<StudyArgs> StudyParams() {
  using io::IntParam, io::TextParam;
  io::ParamTable<StudyArgs> t = {
      TextParam<StudyArgs>("knobs", [](auto& a) -> auto& { return a.knobs; }, "KNOB,KNOB,...",
                           "Knobs to sweep (the others stay at their defaults): " +
                               io::JoinChoices(study::KnobNames(study::DefaultPlans()), ","),
                           "study", CheckKnobs),
      TextParam<StudyArgs>("size", [](auto& a) -> auto& { return a.size; }, "WIDTH[xHEIGHT]", "Image size", "study",
                           [](std::string_view text, const io::SourceLocation& where) {
                             (void)ParseSize(std::string(text), where.ToString());
                           }),
      IntParam<StudyArgs>("views", [](auto& a) -> auto& { return a.views; }, 1, 64, "",
                          "Views, turning about the vertical axis; errors pool their pixels", "study"),
      IntParam<StudyArgs>("repeats", [](auto& a) -> auto& { return a.repeats; }, 1, 1000, "",
                          "Renders of each point and view; times are their median", "study"),
      IntParam<StudyArgs>("reference-rays", [](auto& a) -> auto& { return a.referenceRays; }, 256, 1 << 20, "rays",
                          "Most rays a pixel of the reference AO (it adds rays until its standard error is a "
                          "tenth of the smallest error measured, or this)", "study"),
      TextParam<StudyArgs>("assembly", [](auto& a) -> auto& { return a.assembly; }, "ID", "Build biological assembly ID",
                           "study"),
      IntParam<StudyArgs>("threads", [](auto& a) -> auto& { return a.threads; }, 0, 1024, "",
                          "Worker threads (0: all cores)", "study"),
      TextParam<StudyArgs>("output", [](auto& a) -> auto& { return a.output; }, "DIR",
                           "Folder for the CSVs, summary.md and plots (made if missing)", "study"),
  };
  t.back().shortName = 'o';
  return t;
}

StudyCommand::StudyCommand(CLI::App& app) : params_(StudyParams()) {
  command_ = app.add_subcommand("study", "What each accuracy knob costs in time and error (CSV, summary.md, plots)");
  command_->add_option("MOLECULE", molecule_, "PDB or mmCIF file")->required();
  command_->footer(kStudyHelp);
  params_.AddTo(*command_);
}

StudyArgs StudyCommand::Args() {
  StudyArgs a;
  params_.inputs().CollectFlags();
  a.molecule = molecule_;
  params_.Apply(a);
  return a;
}

int RunStudy(const StudyArgs& a) {
  std::vector<study::MethodPlan> plans = study::DefaultPlans();
  if (!a.knobs.empty()) plans = study::SelectKnobs(plans, SplitCommas(a.knobs), {"--knobs"});
  std::unique_ptr<tbb::global_control> threads;
  if (a.threads > 0)
    threads = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, size_t(a.threads));
  const StudyScene s = LoadScene(a);  // a bad molecule leaves no folder behind
  MakeOutputFolder(a.output);
  study::StudyOptions options;
  options.repeats = a.repeats;
  options.maxReferenceRays = a.referenceRays;
  options.progress = Progress;
  const std::vector<study::MethodResult> results = study::RunStudy(plans, {&s.drawn.scene, s.views}, options);
  WriteOutputs(a, s, results);
  PrintTable(results);
  return io::kExitOk;
}

}  // namespace softmol::cli
