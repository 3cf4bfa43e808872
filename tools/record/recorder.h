// candela-record's engine: capture (V4L2 or libcamera, see
// input/video_capture.h) into a folder that `candela-tool
// ingest` reads unchanged (frames/NNNNNNNN.png + info.txt "NN fps"), plus a
// manifest.json with timestamps, sequence numbers, the camera controls used
// and every dropped frame. Every file is written atomically (temporary file +
// rename) and the manifest is rewritten once a second, so whatever ends the
// recording (frame count, signal, full disk, yanked camera) leaves a
// consistent folder behind.
#pragma once

#include <atomic>
#include <cstdint>
#include <string>
#include <vector>

namespace candela::record {

struct RecordOptions {
  std::string backend = "auto";  // v4l2 | libcamera | auto (libcamera first, then V4L2)
  std::string device = "auto";   // /dev/videoN, a libcamera camera id, or auto (the first)
  std::string out;               // folder; created if missing; must not hold a recording already
  std::string clip;              // default: the folder's name
  int width = 640, height = 480;
  std::string pixel_format;  // e.g. YUYV; empty: the camera's first usable one
  int fps = 30;
  uint64_t frames = 0;     // stop after this many written frames (0: no limit)
  double seconds = 0;      // stop after this long (0: no limit)
  bool color = false;      // RGB PNGs instead of gray (luma)
  bool keep_auto = false;  // leave auto exposure/gain/white balance as they are
  // -1: keep the current value, locked. libcamera: exposure in us, gain as
  // AnalogueGain, white balance not settable (colour gains are kept instead).
  int64_t exposure = -1, gain = -1, white_balance = -1;
  int queue = 48;   // frames buffered between capture and the PNG writers
  int writers = 2;  // PNG writer threads
};

// Something that watches the recorded frames as they go by (the live preview,
// tools/record/preview.h). Kept abstract so the recorder links no GL.
class FrameObserver {
 public:
  virtual ~FrameObserver() = default;
  // The camera is open: frames will be width x height, 1 (gray) or 3 (RGB) channels.
  virtual void start(int width, int height, int channels) = 0;
  // One recorded frame (rows top to bottom, tightly packed). Must return at
  // once: it copies or skips, never waits for the observer.
  virtual void push(const uint8_t* pixels, uint32_t sequence) = 0;
  // The recording is over: shows the last frame and stops the observer.
  virtual void stop() = 0;
  // True once the user asked to stop from it (window closed, Esc or q).
  virtual bool quit_requested() const = 0;
  // A JSON object for the manifest's "preview" key.
  virtual std::string manifest_json() const = 0;
};

struct RecordResult {
  int exit_code = 0;    // 0 ok; see kExit*
  std::string message;  // the clear one-line reason the recording ended
  uint64_t written = 0, dropped = 0;
  double seconds = 0, fps = 0;  // sustained rate of written frames
};

inline constexpr int kExitOk = 0;
inline constexpr int kExitUsage = 2;
inline constexpr int kExitOutput = 3;      // output folder cannot be written (read-only, full)
inline constexpr int kExitCamera = 4;      // no camera / cannot open / unusable format
inline constexpr int kExitCameraLost = 5;  // the camera went away mid-recording

// Runs until done or `stop` becomes true (a signal handler sets it). `preview`
// (optional) sees every recorded frame; it can neither stop nor slow the recording.
RecordResult record(const RecordOptions& options, const std::atomic<bool>& stop,
                    FrameObserver* preview = nullptr);

}  // namespace candela::record
