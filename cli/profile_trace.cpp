#include "cli/profile_trace.h"

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "effects/pass_list.h"
#include "io/error.h"

namespace softmol::cli {

void ProfileTrace::AddComplete(const std::string& name, const std::string& category, double startMs,
                               double durationMs, int track) {
  events_.push_back({{"name", name}, {"cat", category}, {"ph", "X"}, {"pid", 1}, {"tid", track},
                     {"ts", startMs * 1000.0}, {"dur", durationMs * 1000.0}});
}

void ProfileTrace::AddFrame(int index, double startMs, const effects::RenderedFrame& f) {
  AddComplete("frame", "frame", startMs, f.totalMs);
  events_.back()["args"] = {{"index", index}};
  for (const effects::PassTiming& p : f.passes) {
    AddComplete(p.name, "pass", startMs + p.startMs, p.durationMs);
    // What each pass read and wrote (the pass list's declarations), shown beside its bar.
    events_.back()["args"] = {{"reads", effects::BufferNames(p.reads)}, {"writes", effects::BufferNames(p.writes)}};
    if (p.inGBufferTiles) events_.back()["args"]["fused"] = "in gbuffer tiles";
    if (p.name == "gbuffer") {
      // The raster stages run one after another inside the G-buffer pass; the time its tiles
      // spent in a fused pass is that pass's bar.
      double t = startMs + p.startMs;
      const raster::FrameStats& s = f.rasterStats;
      const std::pair<const char*, double> stages[] = {
          {"setup", s.setupMs}, {"binning", s.binningMs}, {"raster", std::max(s.rasterMs - s.consumerMs, 0.0)}};
      for (const auto& [name, ms] : stages) {
        AddComplete(name, "raster", t, ms);
        t += ms;
      }
    }
  }
  const raster::FrameStats& s = f.rasterStats;
  events_.push_back({{"name", "raster counters"}, {"ph", "C"}, {"pid", 1}, {"tid", 1},
                     {"ts", startMs * 1000.0},
                     {"args", {{"primitives set up", s.primitivesSetUp},
                               {"primitives culled", s.primitivesCulled},
                               {"spheres repeated", s.spheresRepeated},
                               {"bin entries", s.binEntries},
                               {"fragments tested", s.fragmentsTested},
                               {"fragments kept", s.fragmentsKept},
                               {"tiles skipped by depth", s.tilesSkippedByDepth}}}});
  if (f.shadowStats.covered > 0) {
    // The PCF pre-test's saving (Sigg §4): samples it decided and map taps taken.
    const effects::ShadowStats& sh = f.shadowStats;
    events_.push_back({{"name", "shadow counters"}, {"ph", "C"}, {"pid", 1}, {"tid", 1},
                       {"ts", startMs * 1000.0},
                       {"args", {{"covered samples", sh.covered},
                                 {"decided by the pre-test", sh.pretestDecided},
                                 {"map taps", sh.tapsTaken}}}});
  }
}

void ProfileTrace::Write(const std::string& path) const {
  const nlohmann::json doc = {{"traceEvents", events_}, {"displayTimeUnit", "ms"}};
  namespace fs = std::filesystem;
  const fs::path p(path);
  // Built piece by piece: GCC 12 misreports "." + std::string under -Wrestrict.
  fs::path tmp = p.parent_path() / ".";
  tmp += p.filename();
  tmp += ".tmp";
  {
    std::ofstream out(tmp);
    out << doc.dump(1) << '\n';
    if (!out) throw io::InputError({"--profile"}, "cannot write '" + path + "'");
  }
  std::error_code ec;
  fs::rename(tmp, p, ec);
  if (ec) {
    fs::remove(tmp, ec);
    throw io::InputError({"--profile"}, "cannot write '" + path + "': " + ec.message());
  }
}

}  // namespace softmol::cli
