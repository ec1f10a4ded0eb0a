// cli/profile_trace.h — collects timings into Chrome trace-event JSON (open in Perfetto or
// chrome://tracing): loading steps, one `frame` event per rendered frame with the passes that
// ran nested inside, the raster stages inside the G-buffer pass, and raster counters.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "effects/frame_renderer.h"

namespace softmol::cli {

class ProfileTrace {
 public:
  // A complete ("X") event; times in ms from the start of the command. Track 1 is the main
  // thread; kWriterTrack holds the image writes that overlap the next frame.
  void AddComplete(const std::string& name, const std::string& category, double startMs, double durationMs,
                   int track = 1);
  static constexpr int kWriterTrack = 2;
  // A frame, its passes and counters, starting at startMs.
  void AddFrame(int index, double startMs, const effects::RenderedFrame& frame);
  // Writes the JSON through a temporary file and a rename.
  void Write(const std::string& path) const;
  const nlohmann::json& Events() const { return events_; }

 private:
  nlohmann::json events_ = nlohmann::json::array();
};

}  // namespace softmol::cli
