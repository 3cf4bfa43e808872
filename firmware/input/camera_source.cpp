#include "input/camera_source.h"

#include <poll.h>
#include <sys/eventfd.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <ctime>
#include <vector>

#include "core/log.h"
#include "input/motion_wind.h"
#include "input/v4l2_capture.h"
#include "input/video_capture.h"

namespace candela {

namespace {
int64_t thread_cpu_ns() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}
}  // namespace

CameraSource::CameraSource(const InputSpec& spec, uint16_t source, const WindSpec& wind,
                           InputEventSink& sink)
    : spec_(spec), source_(source), wind_(wind), sink_(sink) {}

CameraSource::~CameraSource() { stop(); }

void CameraSource::start() {
  wake_fd_ = eventfd(0, EFD_CLOEXEC | EFD_NONBLOCK);
  if (wake_fd_ < 0) {
    set_status("cannot create an eventfd; camera input off", true);
    return;
  }
  thread_ = std::thread([this] { run(); });
}

void CameraSource::stop() {
  if (thread_.joinable()) {
    const uint64_t one = 1;
    if (write(wake_fd_, &one, sizeof one) < 0) LOG_ERROR("camera: cannot wake the camera thread");
    thread_.join();
  }
  if (wake_fd_ >= 0) close(wake_fd_);
  wake_fd_ = -1;
}

std::string CameraSource::status() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return status_;
}

std::string CameraSource::device() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return device_;
}

CameraSource::Stats CameraSource::stats() const {
  return {frames_.load(), gusts_.load(), fps_.load(), cpu_percent_.load()};
}

void CameraSource::set_status(const std::string& status, bool warn) {
  std::lock_guard<std::mutex> lock(mutex_);
  status_ = status;
  if (warn && status != last_logged_) {  // once per distinct reason, not every retry
    LOG_WARN("input \"%s\" (camera): %s; retrying every %d s", spec_.name.c_str(), status.c_str(),
             kRetryMs / 1000);
    last_logged_ = status;
  }
  if (!warn) last_logged_.clear();
}

bool CameraSource::wait(int ms) {
  pollfd p{wake_fd_, POLLIN, 0};
  return poll(&p, 1, ms) > 0;
}

void CameraSource::run() {
  if (spec_.backend == "libcamera" && !libcamera_available()) {
    set_status(
        "the libcamera backend is not built into this candela (libcamera-dev was "
        "missing at build time); use backend = \"v4l2\"",
        true);
    return;
  }
  for (;;) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      device_ = spec_.device;  // until the camera says which it is
    }
    std::unique_ptr<VideoCapture> cap;
    try {
      CaptureSettings s;
      s.device = spec_.device;
      s.width = spec_.width;
      s.height = spec_.height;
      s.fps = spec_.fps;
      s.buffers = 4;
      cap = open_video_capture(spec_.backend, s);
    } catch (const std::exception& e) {
      set_status(e.what(), true);
      if (wait(kRetryMs)) return;
      continue;
    }
    const std::string dev = cap->device();
    {
      std::lock_guard<std::mutex> lock(mutex_);
      device_ = dev;
    }
    const V4l2Format f = cap->format();
    // Work on about the configured size: the largest whole factor that keeps it.
    const int factor = std::max(1, std::min(f.width / spec_.width, f.height / spec_.height));
    const int ww = f.width / factor, wh = f.height / factor;
    std::vector<uint8_t> gray(static_cast<size_t>(f.width) * f.height),
        small(static_cast<size_t>(ww) * wh);
    MotionDetector detector(ww, wh);
    CameraWindLogic logic(spec_, source_, wind_);
    LOG_INFO("input \"%s\" (camera): %s %dx%d %s at %.1f fps, motion on %dx%d", spec_.name.c_str(),
             cap->name().c_str(), f.width, f.height, fourcc_name(f.fourcc).c_str(), f.fps, ww, wh);
    set_status("ok", false);
    int64_t cpu0 = thread_cpu_ns(), wall0 = monotonic_ns();
    uint64_t frames0 = frames_.load();
    int silent_ms = 0;
    for (;;) {
      VideoFrame frame;
      const auto r = cap->next(frame, 1000, wake_fd_);
      if (r == VideoCapture::Result::kWoken) return;
      if (r == VideoCapture::Result::kGone) {
        set_status(dev + ": " + cap->error(), true);
        break;
      }
      if (r == VideoCapture::Result::kTimeout) {
        silent_ms += 1000;
        if (silent_ms >= 5000) {  // streaming but silent: reopen it
          set_status(dev + ": no frames for 5 s", true);
          break;
        }
        continue;
      }
      silent_ms = 0;
      if (frame.bytes && frame_to_gray(f, frame.data, frame.bytes, gray.data())) {
        cap->release(frame);
        const uint8_t* img = gray.data();
        if (factor > 1) {
          downsample_gray(gray.data(), f.width, f.height, factor, small.data());
          img = small.data();
        }
        const uint64_t before = logic.gusts();
        logic.frame(detector.feed(img), frame.timestamp_ns, sink_);
        gusts_.fetch_add(logic.gusts() - before);
        frames_.fetch_add(1);
      } else {
        cap->release(frame);
      }
      const int64_t wall = monotonic_ns();
      if (wall - wall0 >= 2'000'000'000) {  // the thread's own cost, every 2 s
        const double secs = static_cast<double>(wall - wall0) * 1e-9;
        cpu_percent_.store(100.0 * static_cast<double>(thread_cpu_ns() - cpu0) * 1e-9 / secs);
        fps_.store(static_cast<double>(frames_.load() - frames0) / secs);
        cpu0 = thread_cpu_ns(), wall0 = wall, frames0 = frames_.load();
      }
    }
    cap.reset();
    if (wait(kRetryMs)) return;
  }
}

}  // namespace candela
