// cli/main.cpp — the `softmol` command and its one error boundary: every exception ends here as
// one line on stderr and an exit code (io/error.h): 2 bad input (io::InputError, a command line
// CLI11 rejects), 3 internal error (io::InternalError or any other exception: gemmi, TBB,
// OpenImageIO, the standard library), 4 out of memory. Commands write outputs through
// temp-then-rename, so a failure leaves nothing half-written.
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <new>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "cli/commands.h"
#include "cli/heap_policy.h"
#include "io/error.h"
#include "raster/simd_target.h"

namespace {

using namespace softmol;

constexpr const char* kFooter =
    "Exit codes: 0 success; 1 `softmol diff`: the images differ; 2 bad input (a file, record, option or scene key: the message names "
    "it); 3 internal error (not the input's fault); 4 out of memory.\n"
    "SIMD: --simd TARGET (before or after the subcommand) or the environment variable "
    "SOFTMOL_SIMD forces the target of every SIMD kernel (--simd wins); outputs are the same "
    "bytes on every target. --version lists this CPU's targets.";

std::string VersionText() {
  std::string s = "softmol 0.1.0\nSIMD targets on this CPU (best first):";
  for (const auto& t : raster::AvailableSimdTargets()) s += " " + t;
  return s + "\nSIMD target in use: " + raster::ActiveSimdTarget();
}

// A command line CLI11 rejects, as one line like every other softmol error: the option first,
// then what is wrong with it.
std::string ParseErrorMessage(const CLI::App& app, const CLI::ParseError& e) {
  if (dynamic_cast<const CLI::ExtrasError*>(&e)) {
    std::vector<std::string> extra = app.remaining(/*recurse=*/true);
    for (const CLI::App* sub : app.get_subcommands())
      for (const std::string& r : sub->remaining()) extra.push_back(r);
    const std::string first = extra.empty() ? "?" : extra.front();
    std::string help = "softmol --help";
    for (const CLI::App* sub : app.get_subcommands()) help = "softmol " + sub->get_name() + " --help";
    if (!first.empty() && first[0] == '-') return first + ": unknown option (see " + help + ")";
    return "'" + first + "': unexpected argument (quote a value that holds spaces; see " + help + ")";
  }
  return e.what();
}

int Run(CLI::App& app, int argc, char** argv, cli::InfoArgs& info, cli::RenderCommand& render,
        cli::BakeCommand& bake, cli::DiffCommand& diff, cli::StudyCommand& study) {
  if (const char* env = std::getenv("SOFTMOL_SIMD"); env && *env)
    raster::ForceSimdTarget(env, "SOFTMOL_SIMD");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
    std::fprintf(stderr, "softmol: %s\n", ParseErrorMessage(app, e).c_str());
    return io::kExitBadInput;
  }
  if (app.got_subcommand("info")) return cli::RunInfo(info);
  if (app.got_subcommand("render")) return cli::RunRender(render.Args());
  if (app.got_subcommand("bake")) return cli::RunBake(bake.Args());
  if (app.got_subcommand("diff")) return cli::RunDiff(diff.Args());
  if (app.got_subcommand("study")) return cli::RunStudy(study.Args());
  return io::kExitBadInput;
}

}  // namespace

int main(int argc, char** argv) {
  cli::KeepFreedMemoryInTheHeap();
  try {
    CLI::App app{"softmol — renders molecules on the CPU (quadric impostors, AO, edge cueing)"};
    app.require_subcommand(1);
    app.footer(kFooter);
    app.fallthrough();  // global options (--simd) also after the subcommand
    app.set_version_flag("--version", VersionText);
    app.add_option_function<std::string>(
           "--simd", [](const std::string& t) { raster::ForceSimdTarget(t, "--simd"); },
           "Force the SIMD target: scalar|ssse3|sse4|avx2|avx3|... (see --version)")
        ->trigger_on_parse();
    cli::InfoArgs info;
    cli::AddInfoCommand(app, info);
    cli::RenderCommand render(app);
    cli::BakeCommand bake(app);
    cli::DiffCommand diff(app);
    cli::StudyCommand study(app);
    return Run(app, argc, argv, info, render, bake, diff, study);
  } catch (const io::InputError& e) {
    std::fprintf(stderr, "softmol: %s\n", e.what());
    return io::kExitBadInput;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "softmol: out of memory\n");
    return io::kExitOutOfMemory;
  } catch (const io::InternalError& e) {
    std::fprintf(stderr, "softmol: %s\n", e.what());
    return io::kExitInternal;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "softmol: internal error: %s\n", e.what());
    return io::kExitInternal;
  } catch (...) {
    std::fprintf(stderr, "softmol: internal error: unknown exception\n");
    return io::kExitInternal;
  }
}
