// What the camera input and candela-record need from a camera, whatever
// captures it: plain V4L2 (USB webcams, vivid) or libcamera (Raspberry Pi
// cameras, vimc). open_video_capture() picks the backend; nothing outside
// libcamera_capture.cpp includes libcamera headers. Library candela_v4l2:
// no GL, no Eigen.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace candela {

// A frame's layout, always as a V4L2 fourcc (libcamera's formats are mapped).
struct VideoFormat {
  uint32_t fourcc = 0;
  int width = 0, height = 0;
  int bytesperline = 0;
  size_t sizeimage = 0;
  double fps = 0;  // 0: the camera does not say
};

struct VideoFrame {
  const uint8_t* data = nullptr;  // the first plane (luma for NV12/YU12)
  size_t bytes = 0;               // 0: a damaged frame, skip it (still release it)
  uint32_t sequence = 0;
  int64_t timestamp_ns = 0;  // the camera's (CLOCK_MONOTONIC for nearly all)
  int index = -1;            // buffer to hand back with release()
};

struct CaptureSettings {
  // V4L2: /dev/videoN. libcamera: a camera id (`cam -l`) or "auto" (the first).
  std::string device;
  int width = 640, height = 480;
  uint32_t fourcc = 0;  // 0: the first of GREY, YUYV, UYVY, NV12, YU12, RGB3, BGR3 offered
  int fps = 30;         // 0: leave the camera's rate
  int buffers = 6;
};

// One camera control as the manifest shows it; values are JSON text
// ("null" when the camera does not tell).
struct CaptureControl {
  uint32_t id = 0;
  std::string name, value_json, default_json;
};

// What lock_auto() should do: turn auto exposure, gain and white balance off,
// keeping the values in use unless given (-1: keep).
struct AutoLockRequest {
  bool keep_auto = false;  // leave every auto control as it is
  int64_t exposure = -1, gain = -1, white_balance = -1;
};
// What lock_auto() did to one control: "off", "kept at 24", "not offered"...
struct LockedControl {
  std::string name, outcome;
};

class VideoCapture {
 public:
  enum class Result { kFrame, kTimeout, kWoken, kGone };
  virtual ~VideoCapture() = default;

  // Waits up to timeout_ms for a frame (or for wake_fd to become readable).
  // kGone: the camera disappeared or failed for good; error() says how.
  virtual Result next(VideoFrame& frame, int timeout_ms, int wake_fd = -1) = 0;
  // Hands a frame's buffer back to the camera.
  virtual void release(const VideoFrame& frame) = 0;

  virtual const VideoFormat& format() const = 0;
  virtual const std::string& error() const = 0;
  virtual const char* backend() const = 0;             // "v4l2" | "libcamera"
  virtual const std::string& device() const = 0;       // /dev/videoN or the camera id
  virtual const std::string& card() const = 0;         // the camera's model name
  virtual const std::string& driver() const = 0;       // kernel driver or pipeline handler
  std::string name() const;                            // for logs: device (card) via backend
  virtual std::vector<CaptureControl> controls() = 0;  // for the manifest
  // Auto exposure jumps ruin a dataset: lock what the camera offers.
  virtual std::vector<LockedControl> lock_auto(const AutoLockRequest& request) = 0;
};

// backend: "v4l2", "libcamera" or "auto". Auto: a /dev path is V4L2;
// otherwise libcamera first, then V4L2, with one log line saying which and
// why. settings.device "auto": the first camera of that backend. Throws
// RuntimeError naming the camera and what failed (absent, busy, not built).
std::unique_ptr<VideoCapture> open_video_capture(const std::string& backend,
                                                 const CaptureSettings& settings);

// Whether this build has the libcamera backend (pkg-config libcamera found).
bool libcamera_available();

// A libcamera (DRM) pixel format's fourcc -> the V4L2 fourcc with the same
// memory layout (DRM BGR888 is V4L2 RGB3); 0 for formats candela cannot read.
uint32_t v4l2_fourcc_from_libcamera(uint32_t drm_fourcc);
// The reverse, for asking libcamera for a V4L2 format; 0 if none.
uint32_t libcamera_fourcc_from_v4l2(uint32_t v4l2_fourcc);

}  // namespace candela
