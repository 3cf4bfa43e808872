// candela-record's live preview: the newest recorded frame on the display
// (an X11 window, the DRM/KMS screen, or headless for tests), drawn by a
// thread of its own with its own EGL context. The recorder hands frames over
// through a wait-free triple buffer: a slow preview skips frames, the
// recording never waits for it, and a preview that cannot open or breaks
// down is logged once and leaves the recording alone.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "recorder.h"

namespace candela::record {

struct PreviewOptions {
  std::string mode = "auto";  // auto | off | window | drm | headless
  int width = 0, height = 0;  // 0: the frame's size (window, headless), the preferred mode (drm)
  std::string drm_device;     // empty: the first card with a free connected connector
  std::string dump_dir;       // writes DIR/preview.png (the last image shown) at the end
};

// What `mode` means here and now: the backends to try, in order (none for
// "off"), and a sentence saying why. auto: a window when $DISPLAY is set,
// else the DRM screen if one is connected and free, else nothing.
struct PreviewChoice {
  std::vector<std::string> backends;
  std::string why;
};
// Throws std::invalid_argument for an unknown mode.
PreviewChoice choose_preview(const std::string& mode, const char* display_env);

// Where a fw x fh frame goes on a dw x dh screen, aspect kept (rows top down).
struct PreviewRect {
  int x = 0, y = 0, width = 0, height = 0;
};
PreviewRect letterbox(int fw, int fh, int dw, int dh);
// The red "recording" dot in the top left corner of a dw x dh screen.
PreviewRect recording_dot(int dw, int dh);

class RecordPreview final : public FrameObserver {
 public:
  // `on_quit` runs (on the preview's thread) when the user closes the window
  // or presses Esc or q: candela-record stops the recording as on Ctrl-C.
  RecordPreview(PreviewOptions options, std::function<void()> on_quit);
  ~RecordPreview() override;
  RecordPreview(const RecordPreview&) = delete;
  RecordPreview& operator=(const RecordPreview&) = delete;

  void start(int width, int height, int channels) override;
  void push(const uint8_t* pixels, uint32_t sequence) override;
  void stop() override;
  bool quit_requested() const override { return quit_.load(); }
  std::string manifest_json() const override;

  // Blocks until the preview has opened or given up (tests; the recorder never waits).
  bool wait_until_open();
  uint64_t shown() const { return shown_.load(); }
  uint64_t offered() const { return offered_.load(); }
  std::string backend() const;  // "" until open
  std::string error() const;    // why it could not open or stopped; "" if fine
  // One line for candela-record's summary, e.g. "preview on drm showed 57 of 60 frames".
  std::string summary() const;

 private:
  enum class State { kIdle, kOpening, kOpen, kFailed, kOff };
  void run();
  bool take_newest();
  void set_state(State s, const std::string& backend, const std::string& error);

  PreviewOptions options_;
  PreviewChoice choice_;
  std::function<void()> on_quit_;
  int width_ = 0, height_ = 0, channels_ = 0;
  size_t frame_bytes_ = 0;

  // Triple buffer: the recorder fills back_, then swaps it with the middle
  // slot (index in middle_, with kFresh set); the preview swaps the middle
  // with front_ when kFresh is set. No lock, no waiting on either side.
  static constexpr unsigned kFresh = 4;
  std::vector<uint8_t> buffers_[3];
  uint32_t sequences_[3] = {};
  unsigned back_ = 0, front_ = 2;
  std::atomic<unsigned> middle_{1};
  std::atomic<bool> accepting_{false};

  std::atomic<bool> stopping_{false}, quit_{false};
  std::atomic<uint64_t> shown_{0}, offered_{0};
  std::atomic<int64_t> last_shown_sequence_{-1};
  std::mutex wake_mutex_;
  std::condition_variable wake_;

  mutable std::mutex status_mutex_;
  std::condition_variable status_changed_;
  State state_ = State::kIdle;
  std::string backend_, error_;
  int display_width_ = 0, display_height_ = 0;

  std::thread thread_;
};

}  // namespace candela::record
