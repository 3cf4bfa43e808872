// The camera input's thread: opens the camera (open_video_capture: V4L2 or
// libcamera, by the input's `backend`; device "auto" takes the first camera), turns frames into
// small gray images, finds motion and emits gusts. An absent, busy or unplugged camera is logged
// once per reason and retried every few seconds; the display never waits for it.
#pragma once

#include <atomic>
#include <mutex>
#include <string>
#include <thread>

#include "input/input_event.h"
#include "scene/input_spec.h"
#include "wind/wind_field.h"

namespace candela {

class CameraSource {
 public:
  CameraSource(const InputSpec& spec, uint16_t source, const WindSpec& wind, InputEventSink& sink);
  ~CameraSource();
  void start();
  void stop();

  uint16_t source() const { return source_; }
  std::string status() const;
  std::string device() const;
  // What `state` reports of the camera besides its status.
  struct Stats {
    uint64_t frames = 0, gusts = 0;
    double fps = 0, cpu_percent = 0;
  };
  Stats stats() const;

  static constexpr int kRetryMs = 2000;

 private:
  void run();
  void set_status(const std::string& status, bool warn);
  bool wait(int ms);  // true: asked to stop

  InputSpec spec_;
  uint16_t source_;
  WindSpec wind_;
  InputEventSink& sink_;
  int wake_fd_ = -1;
  std::thread thread_;
  mutable std::mutex mutex_;
  std::string status_ = "not opened yet", device_, last_logged_;
  std::atomic<uint64_t> frames_{0}, gusts_{0};
  std::atomic<double> fps_{0}, cpu_percent_{0};
};

}  // namespace candela
