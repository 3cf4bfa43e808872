// Plain V4L2 video capture (USB webcams, vivid): mmap streaming with a poll
// timeout, so a dead camera cannot hang the caller; EINTR retried; the
// driver's bytesperline/sizeimage sanitised. Shared by the runtime's camera
// input and candela-record (library candela_v4l2: no GL, no Eigen).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace candela {

struct V4l2Format {
  uint32_t fourcc = 0;
  int width = 0, height = 0;
  int bytesperline = 0;
  size_t sizeimage = 0;
  double fps = 0;  // 0: the driver does not say
};
std::string fourcc_name(uint32_t fourcc);
// "YUYV" -> fourcc; 0 for anything but 4 characters.
uint32_t fourcc_from_name(const std::string& name);

struct V4l2Frame {
  const uint8_t* data = nullptr;
  size_t bytes = 0;
  uint32_t sequence = 0;
  int64_t timestamp_ns = 0;  // the driver's (CLOCK_MONOTONIC for nearly all)
  int index = -1;            // buffer to hand back with release()
};

struct V4l2Control {
  uint32_t id = 0;
  std::string name;
  int type = 0;  // V4L2_CTRL_TYPE_*
  int64_t minimum = 0, maximum = 0, step = 0, default_value = 0;
  int64_t value = 0;
  bool read_only = false, inactive = false;
};

class V4l2Capture {
 public:
  struct Settings {
    std::string device;  // /dev/videoN
    int width = 640, height = 480;
    uint32_t fourcc = 0;  // 0: the first of GREY, YUYV, UYVY, NV12, YU12, RGB3, BGR3 offered
    int fps = 30;         // 0: leave the driver's rate
    int buffers = 6;
  };
  // Opens, negotiates the nearest size/format/rate and starts streaming.
  // Throws RuntimeError saying what failed (absent, busy, not a capture device...).
  explicit V4l2Capture(const Settings& settings);
  ~V4l2Capture();
  V4l2Capture(const V4l2Capture&) = delete;
  V4l2Capture& operator=(const V4l2Capture&) = delete;

  enum class Result { kFrame, kTimeout, kWoken, kGone };
  // Waits up to timeout_ms for a frame (or for wake_fd to become readable).
  // kGone: the device disappeared or failed for good; `error` says how.
  Result next(V4l2Frame& frame, int timeout_ms, int wake_fd = -1);
  // Hands a frame's buffer back to the driver.
  void release(const V4l2Frame& frame);

  const V4l2Format& format() const { return format_; }
  const std::string& device() const { return device_; }
  const std::string& card() const { return card_; }
  const std::string& driver() const { return driver_; }
  const std::string& error() const { return error_; }
  int fd() const { return fd_; }

  std::vector<V4l2Control> controls();
  std::optional<int64_t> get_control(uint32_t id);
  // False (and `why`) when the device lacks it or refuses the value.
  bool set_control(uint32_t id, int64_t value, std::string& why);

 private:
  struct Buffer {
    void* start = nullptr;
    size_t length = 0;
  };
  void close_all();
  std::string device_, card_, driver_, error_;
  int fd_ = -1;
  V4l2Format format_;
  std::vector<Buffer> buffers_;
  bool streaming_ = false;
};

// Video capture nodes in /dev (sorted), for "auto".
std::vector<std::string> find_capture_devices();

// Luma of one frame, `format` as negotiated, into a width x height gray buffer
// (`out` must hold that much). False for formats it does not know.
bool frame_to_gray(const V4l2Format& format, const uint8_t* data, size_t bytes, uint8_t* out);
// Whether frame_to_gray (and the recorder's colour path) understand it.
bool is_supported_format(uint32_t fourcc);
// RGB (8-bit, 3 channels) from YUYV/UYVY/RGB3/BGR3/GREY; false for others.
bool frame_to_rgb(const V4l2Format& format, const uint8_t* data, size_t bytes, uint8_t* out);

}  // namespace candela
