// manifest.json: what was recorded (camera, format, controls) and how it
// went (every written frame, every dropped one, the preview, how it ended),
// written with nlohmann_json in a fixed key order (tools/record/README.md
// lists the keys); only the long frames array is formatted directly, as it is
// rewritten every second.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "input/video_capture.h"
#include "png_writer_pool.h"

namespace candela::record {

// What stays fixed for a recording.
struct RecordingInfo {
  std::string clip, backend, device, card, driver;
  std::string started;  // UTC, ISO 8601
  int width = 0, height = 0;
  std::string pixel_format;  // V4L2 name, e.g. YUYV
  bool color = false;        // rgb8 PNGs, else gray8
  double fps = 0;            // negotiated (or asked for when the camera reports none)
  int requested_fps = 0;
  std::vector<CaptureControl> controls;
  std::vector<LockedControl> locked;
};

// How the recording stands when the manifest is written.
struct RecordingState {
  std::vector<WrittenFrame> frames;  // in sequence order
  std::vector<uint32_t> dropped;
  double measured_fps = 0;
  std::string preview_json;  // a JSON object; empty: {"mode":"off"}
  bool final_write = false;  // false: "complete": false, "end_reason": "recording"
  bool complete = false;
  std::string end_reason;
};

// The manifest's text (JSON, ending in a newline).
std::string manifest_text(const RecordingInfo& info, const RecordingState& state);

// Current UTC time as 2026-01-31T12:00:00Z.
std::string utc_now();

}  // namespace candela::record
