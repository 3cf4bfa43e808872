// Plain V4L2 video capture (USB webcams, vivid): mmap streaming with a poll
// timeout, so a dead camera cannot hang the caller; EINTR retried; the
// driver's bytesperline/sizeimage sanitised. One VideoCapture backend (see
// video_capture.h); the frame conversions below serve every backend.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "input/video_capture.h"

namespace candela {

using V4l2Format = VideoFormat;
std::string fourcc_name(uint32_t fourcc);
// "YUYV" -> fourcc; 0 for anything but 4 characters.
uint32_t fourcc_from_name(const std::string& name);

using V4l2Frame = VideoFrame;

struct V4l2Control {
  uint32_t id = 0;
  std::string name;
  int type = 0;  // V4L2_CTRL_TYPE_*
  int64_t minimum = 0, maximum = 0, step = 0, default_value = 0;
  int64_t value = 0;
  bool read_only = false, inactive = false;
};

class V4l2Capture final : public VideoCapture {
 public:
  using Settings = CaptureSettings;  // device: /dev/videoN
  // Opens, negotiates the nearest size/format/rate and starts streaming.
  // Throws RuntimeError saying what failed (absent, busy, not a capture device...).
  explicit V4l2Capture(const Settings& settings);
  ~V4l2Capture();
  V4l2Capture(const V4l2Capture&) = delete;
  V4l2Capture& operator=(const V4l2Capture&) = delete;

  Result next(VideoFrame& frame, int timeout_ms, int wake_fd = -1) override;
  void release(const VideoFrame& frame) override;

  const VideoFormat& format() const override { return format_; }
  const std::string& device() const override { return device_; }
  const std::string& card() const override { return card_; }
  const std::string& driver() const override { return driver_; }
  const std::string& error() const override { return error_; }
  const char* backend() const override { return "v4l2"; }
  int fd() const { return fd_; }

  std::vector<CaptureControl> controls() override;
  // V4L2: exposure_auto manual, autogain and auto white balance off.
  std::vector<LockedControl> lock_auto(const AutoLockRequest& request) override;

  std::vector<V4l2Control> v4l2_controls();
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
