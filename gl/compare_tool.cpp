// gl/compare_tool.cpp — softmol_gl_compare: renders one molecule with the CPU backend and the
// GL mirror, compares every buffer (gl/compare.h), prints the report, optionally writes one
// image per buffer of where the two differ (red on dark grey), and times both.
//   softmol_gl_compare MOLECULE [--size 640x480] [--style spacefill|balls|licorice|ellipsoids]
//                      [--threads N] [--repeat N] [--diff PREFIX] [--highlight SELECTION]
//                      [pass options: --ssaa N,
//                      --shadows, --ao cone, --outlines, ... as `softmol render` takes them]
// Set LP_NUM_THREADS=N as well to give llvmpipe the same thread count as the CPU backend.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <tbb/global_control.h>

#include "common/timer.h"
#include "effects/frame_renderer.h"
#include "effects/pass_list.h"
#include "io/error.h"
#include "gl/compare.h"
#include "gl/context_egl.h"
#include "gl/frame_renderer.h"
#include "io/bonds.h"
#include "io/image_io.h"
#include "io/selection.h"
#include "io/structure_reader.h"
#include "raster/camera.h"
#include "raster/representation.h"

namespace {

using namespace softmol;

struct Args {
  std::string molecule, style = "spacefill", diffPrefix, highlight;
  int width = 640, height = 480, threads = 0, repeat = 0;
  effects::RenderOptions options;  // every pass option, as `softmol render` takes it
};

[[noreturn]] void Usage(const char* why) {
  std::fprintf(stderr,
               "softmol_gl_compare: %s\nusage: softmol_gl_compare MOLECULE [--size WxH] [--style S] "
               "[--threads N] [--repeat N] [--diff PREFIX] [--highlight SELECTION] [any pass option of softmol render: --ssaa N, "
               "--shadows, --ao cone, ...]\n",
               why);
  std::exit(2);
}

// A pass option by its declaration (effects/pass_list.h RenderParams): the same names, ranges
// and messages as `softmol render`.
void SetPassOption(Args& a, const std::string& name, int argc, char** argv, int& i) {
  static const io::ParamTable<effects::RenderOptions> params = effects::RenderParams();
  for (const io::Param<effects::RenderOptions>& p : params) {
    if (p.name != name) continue;
    std::string text = p.isSwitch ? "true" : p.implicitValue;
    const bool hasValue = i + 1 < argc && argv[i + 1][0] != '-';
    if (!p.isSwitch && (hasValue || p.implicitValue.empty())) {
      if (i + 1 >= argc) Usage(("missing value after --" + name).c_str());
      text = argv[++i];
    }
    try {
      p.set(a.options, text, io::FlagLocation(name));
    } catch (const io::InputError& e) {
      Usage(e.what());
    }
    return;
  }
  Usage(("unknown option --" + name).c_str());
}

Args Parse(int argc, char** argv) {
  Args a;
  for (int i = 1; i < argc; ++i) {
    const std::string s = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) Usage(("missing value after " + s).c_str());
      return argv[++i];
    };
    if (s == "--size") {
      const std::string v = value();
      if (std::sscanf(v.c_str(), "%dx%d", &a.width, &a.height) != 2 || a.width <= 0 || a.height <= 0)
        Usage("--size must be WIDTHxHEIGHT");
    } else if (s == "--style") a.style = value();
    else if (s == "--threads") a.threads = std::atoi(value().c_str());
    else if (s == "--repeat") a.repeat = std::atoi(value().c_str());
    else if (s == "--diff") a.diffPrefix = value();
    else if (s == "--highlight") a.highlight = value();
    else if (s.size() > 2 && s[0] == '-' && s[1] == '-') SetPassOption(a, s.substr(2), argc, argv, i);
    else if (!s.empty() && s[0] == '-') Usage(("unknown option " + s).c_str());
    else a.molecule = s;
  }
  if (a.molecule.empty()) Usage("no MOLECULE");
  try {
    effects::CheckRenderOptions(a.options);
  } catch (const io::InputError& e) {
    Usage(e.what());
  }
  return a;
}

raster::Style StyleOf(const std::string& s) {
  if (s == "spacefill") return raster::Style::kSpacefill;
  if (s == "balls") return raster::Style::kBalls;
  if (s == "licorice") return raster::Style::kLicorice;
  if (s == "ellipsoids") return raster::Style::kEllipsoids;
  Usage("unknown --style");
}

// Red where the buffer differs, dark grey elsewhere; top row first (file order).
void WriteDiffImage(const std::string& path, const gl::BufferComparison& c, const gl::BackendReport& r) {
  const int w = c.differs.size() == size_t(r.sampleWidth) * size_t(r.sampleHeight) ? r.sampleWidth : r.cpu.width;
  const int h = int(c.differs.size() / size_t(w));
  std::vector<uint8_t> px(3 * c.differs.size(), 0);
  for (int row = 0; row < h; ++row)
    for (int x = 0; x < w; ++x) {
      const size_t m = size_t(h - 1 - row) * size_t(w) + size_t(x);
      uint8_t* p = &px[3 * (size_t(row) * size_t(w) + size_t(x))];
      if (c.differs[m]) p[0] = 255;
      else p[0] = p[1] = p[2] = 40;
    }
  io::WritePng(path, w, h, 3, px);
}

double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  const Args a = Parse(argc, argv);
  std::string why;
  std::unique_ptr<gl::Context> context = gl::Context::Create(why);
  if (!context) {
    std::fprintf(stderr, "softmol_gl_compare: no GL context: %s\n", why.c_str());
    return 1;
  }
  std::unique_ptr<tbb::global_control> threads;
  if (a.threads > 0)
    threads = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, size_t(a.threads));
  try {
    const raster::Style style = StyleOf(a.style);
    io::Molecule mol = io::ReadMolecule(a.molecule);
    if (style == raster::Style::kBalls || style == raster::Style::kLicorice) io::ComputeDistanceBonds(mol);
    raster::RepresentationOptions rep;
    rep.style = style;
    const raster::PrimitiveScene scene = raster::BuildRepresentation(mol, rep);
    const raster::Camera camera = raster::DefaultCamera(scene, a.width, a.height);
    effects::RenderOptions options = a.options;
    // As `softmol render --highlight`: one flag per atom, which is one sphere per atom in the
    // per-atom styles.
    if (!a.highlight.empty()) options.highlight.spheres = io::Evaluate(io::ParseSelection(a.highlight), mol);
    for (const effects::PlannedPass& p : effects::PlanPasses(options))
      if (!gl::Mirrors(p.id)) throw std::runtime_error(std::string("the pass '") + p.name + "' (" +
                                                       effects::Pass(p.id).enabledBy + ") is not mirrored in GL");

    gl::FrameRenderer renderer;
    std::printf("GL: %s | %s | LP_NUM_THREADS=%s\n", context->renderer().c_str(),
                context->version().c_str(), std::getenv("LP_NUM_THREADS") ? std::getenv("LP_NUM_THREADS") : "(unset)");
    std::printf("scene: %s, %s, %zu primitives, %dx%d, ssaa %d\n", a.molecule.c_str(), a.style.c_str(),
                scene.size(), a.width, a.height, options.ssaa);
    std::printf("passes:");
    for (const effects::PlannedPass& p : effects::PlanPasses(options)) std::printf(" [%s]", p.name);
    std::printf("\n");
    const gl::BackendReport r = gl::CompareBackends(renderer, scene, camera, options);
    for (const gl::BufferComparison& c : r.buffers) {
      std::fputs(gl::FormatComparison(c).c_str(), stdout);
      if (!a.diffPrefix.empty()) {
        std::string name = c.name.substr(0, c.name.find(' ') == std::string::npos ? c.name.size() : c.name.find(' '));
        if (c.name.find("8-bit") != std::string::npos) name += "8";
        WriteDiffImage(a.diffPrefix + name + ".diff.png", c, r);
      }
    }
    if (a.repeat > 0) {
      // Both backends render the whole frame (G-buffer + shading + resolve) into host memory:
      // the GL time includes setup, upload and read-back, which the CPU backend does not need.
      effects::FrameResources resources;
      effects::RenderedFrame f;
      std::vector<double> cpuMs, glMs, glDrawMs, glGbufferMs, glShadingMs, glReadbackMs, glSetupMs;
      effects::RenderFrame(scene, camera, options, f, &resources);  // warm-up
      renderer.RenderFrame(scene, camera, options, f);
      for (int i = 0; i < a.repeat; ++i) {
        auto t0 = Clock::now();
        effects::RenderFrame(scene, camera, options, f, &resources);
        cpuMs.push_back(MsSince(t0));
        t0 = Clock::now();
        const gl::GlFrameStats s = renderer.RenderFrame(scene, camera, options, f);
        glMs.push_back(MsSince(t0));
        glDrawMs.push_back(s.gbufferMs + s.shadingMs);
        glSetupMs.push_back(s.setupMs + s.uploadMs);
        glGbufferMs.push_back(s.gbufferMs);
        glShadingMs.push_back(s.shadingMs);
        glReadbackMs.push_back(s.readbackMs);
      }
      std::printf("timing (median of %d): cpu %.2f ms, gl %.2f ms (gl passes only %.2f ms), gl/cpu %.2f\n",
                  a.repeat, Median(cpuMs), Median(glMs), Median(glDrawMs), Median(glMs) / Median(cpuMs));
      std::printf("best: cpu %.2f ms, gl %.2f ms, gl/cpu %.2f\n", *std::min_element(cpuMs.begin(), cpuMs.end()),
                  *std::min_element(glMs.begin(), glMs.end()),
                  *std::min_element(glMs.begin(), glMs.end()) / *std::min_element(cpuMs.begin(), cpuMs.end()));
      std::printf("gl breakdown (median ms): setup+upload %.2f, gbuffer %.2f, shading %.2f, readback %.2f\n",
                  Median(glSetupMs), Median(glGbufferMs), Median(glShadingMs), Median(glReadbackMs));
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "softmol_gl_compare: %s\n", e.what());
    return 1;
  }
  return 0;
}
