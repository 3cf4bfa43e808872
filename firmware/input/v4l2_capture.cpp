#include "input/v4l2_capture.h"

#include <dirent.h>
#include <fcntl.h>
#include <linux/videodev2.h>
#include <poll.h>
#include <sys/ioctl.h>
#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

#include "core/error.h"

namespace candela {
namespace {

int xioctl(int fd, unsigned long request, void* arg) {
  int r;
  do r = ioctl(fd, request, arg);
  while (r < 0 && errno == EINTR);
  return r;
}

// Bytes per pixel of the first (or only) plane; 0: unknown.
int bytes_per_pixel(uint32_t f) {
  switch (f) {
    case V4L2_PIX_FMT_GREY:
    case V4L2_PIX_FMT_NV12:
    case V4L2_PIX_FMT_YUV420:
      return 1;
    case V4L2_PIX_FMT_YUYV:
    case V4L2_PIX_FMT_UYVY:
      return 2;
    case V4L2_PIX_FMT_RGB24:
    case V4L2_PIX_FMT_BGR24:
      return 3;
    default:
      return 0;
  }
}

size_t min_image_size(uint32_t f, int bpl, int h) {
  const size_t luma = static_cast<size_t>(bpl) * h;
  return f == V4L2_PIX_FMT_NV12 || f == V4L2_PIX_FMT_YUV420 ? luma + luma / 2 : luma;
}

std::string errstr(const std::string& what) { return what + ": " + std::strerror(errno); }

}  // namespace

std::string fourcc_name(uint32_t f) {
  std::string s(4, ' ');
  for (int i = 0; i < 4; ++i) {
    const char c = static_cast<char>((f >> (8 * i)) & 0xFF);
    s[i] = c >= 32 && c < 127 ? c : '?';
  }
  return s;
}

uint32_t fourcc_from_name(const std::string& n) {
  if (n.size() != 4) return 0;
  return v4l2_fourcc(n[0], n[1], n[2], n[3]);
}

bool is_supported_format(uint32_t f) { return bytes_per_pixel(f) != 0; }

V4l2Capture::V4l2Capture(const Settings& s) : device_(s.device) {
  fd_ = open(s.device.c_str(), O_RDWR | O_NONBLOCK | O_CLOEXEC);
  if (fd_ < 0) throw RuntimeError(errstr("camera " + s.device + ": cannot open"));
  try {
    v4l2_capability cap{};
    if (xioctl(fd_, VIDIOC_QUERYCAP, &cap) < 0)
      throw RuntimeError(errstr("camera " + s.device + ": not a V4L2 device"));
    card_ = reinterpret_cast<const char*>(cap.card);
    driver_ = reinterpret_cast<const char*>(cap.driver);
    const uint32_t caps =
        cap.capabilities & V4L2_CAP_DEVICE_CAPS ? cap.device_caps : cap.capabilities;
    if (!(caps & V4L2_CAP_VIDEO_CAPTURE))
      throw RuntimeError("camera " + s.device + " (" + card_ +
                         "): not a single-planar video capture device");
    if (!(caps & V4L2_CAP_STREAMING))
      throw RuntimeError("camera " + s.device + " (" + card_ + "): no streaming I/O");

    uint32_t fourcc = s.fourcc;
    if (!fourcc) {
      std::vector<uint32_t> offered;
      v4l2_fmtdesc d{};
      d.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
      while (xioctl(fd_, VIDIOC_ENUM_FMT, &d) == 0) {
        offered.push_back(d.pixelformat);
        ++d.index;
      }
      for (uint32_t want :
           {V4L2_PIX_FMT_GREY, V4L2_PIX_FMT_YUYV, V4L2_PIX_FMT_UYVY, V4L2_PIX_FMT_NV12,
            V4L2_PIX_FMT_YUV420, V4L2_PIX_FMT_RGB24, V4L2_PIX_FMT_BGR24})
        if (std::find(offered.begin(), offered.end(), want) != offered.end()) {
          fourcc = want;
          break;
        }
      if (!fourcc)
        throw RuntimeError("camera " + s.device + " (" + card_ + "): offers no format " +
                           "candela reads (GREY, YUYV, UYVY, NV12, YU12, RGB3, BGR3)");
    }
    v4l2_format fmt{};
    fmt.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    fmt.fmt.pix.width = static_cast<uint32_t>(s.width);
    fmt.fmt.pix.height = static_cast<uint32_t>(s.height);
    fmt.fmt.pix.pixelformat = fourcc;
    fmt.fmt.pix.field = V4L2_FIELD_NONE;
    if (xioctl(fd_, VIDIOC_S_FMT, &fmt) < 0)
      throw RuntimeError(errno == EBUSY ? "camera " + s.device + " (" + card_ +
                                              "): busy (in use by another program)"
                                        : errstr("camera " + s.device + ": cannot set the format"));
    if (fmt.fmt.pix.pixelformat != fourcc)
      throw RuntimeError("camera " + s.device + " (" + card_ + "): does not offer " +
                         fourcc_name(fourcc));
    format_.fourcc = fourcc;
    format_.width = static_cast<int>(fmt.fmt.pix.width);
    format_.height = static_cast<int>(fmt.fmt.pix.height);
    // Some drivers report 0 or too small a stride/size: never trust less than the minimum.
    const int min_bpl = format_.width * bytes_per_pixel(fourcc);
    format_.bytesperline = std::max(static_cast<int>(fmt.fmt.pix.bytesperline), min_bpl);
    format_.sizeimage = std::max<size_t>(
        fmt.fmt.pix.sizeimage, min_image_size(fourcc, format_.bytesperline, format_.height));

    if (s.fps > 0) {
      v4l2_streamparm parm{};
      parm.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
      if (xioctl(fd_, VIDIOC_G_PARM, &parm) == 0 &&
          (parm.parm.capture.capability & V4L2_CAP_TIMEPERFRAME)) {
        parm.parm.capture.timeperframe = {1, static_cast<uint32_t>(s.fps)};
        xioctl(fd_, VIDIOC_S_PARM, &parm);  // the driver picks the nearest it has
      }
    }
    v4l2_streamparm parm{};
    parm.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    if (xioctl(fd_, VIDIOC_G_PARM, &parm) == 0 && parm.parm.capture.timeperframe.numerator)
      format_.fps = static_cast<double>(parm.parm.capture.timeperframe.denominator) /
                    parm.parm.capture.timeperframe.numerator;

    v4l2_requestbuffers req{};
    req.count = static_cast<uint32_t>(std::max(2, s.buffers));
    req.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    req.memory = V4L2_MEMORY_MMAP;
    if (xioctl(fd_, VIDIOC_REQBUFS, &req) < 0)
      throw RuntimeError(errno == EBUSY ? "camera " + s.device + " (" + card_ +
                                              "): busy (streaming for another program)"
                                        : errstr("camera " + s.device + ": cannot get buffers"));
    if (req.count < 2)
      throw RuntimeError("camera " + s.device + ": the driver gave fewer than 2 buffers");
    for (uint32_t i = 0; i < req.count; ++i) {
      v4l2_buffer b{};
      b.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
      b.memory = V4L2_MEMORY_MMAP;
      b.index = i;
      if (xioctl(fd_, VIDIOC_QUERYBUF, &b) < 0)
        throw RuntimeError(errstr("camera " + s.device + ": QUERYBUF"));
      void* p = mmap(nullptr, b.length, PROT_READ | PROT_WRITE, MAP_SHARED, fd_, b.m.offset);
      if (p == MAP_FAILED) throw RuntimeError(errstr("camera " + s.device + ": mmap"));
      buffers_.push_back({p, b.length});
      if (xioctl(fd_, VIDIOC_QBUF, &b) < 0)
        throw RuntimeError(errstr("camera " + s.device + ": QBUF"));
    }
    v4l2_buf_type type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    if (xioctl(fd_, VIDIOC_STREAMON, &type) < 0)
      throw RuntimeError(errstr("camera " + s.device + ": cannot start streaming"));
    streaming_ = true;
  } catch (...) {
    close_all();
    throw;
  }
}

V4l2Capture::~V4l2Capture() { close_all(); }

void V4l2Capture::close_all() {
  if (fd_ < 0) return;
  if (streaming_) {
    v4l2_buf_type type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    xioctl(fd_, VIDIOC_STREAMOFF, &type);
    streaming_ = false;
  }
  for (auto& b : buffers_) munmap(b.start, b.length);
  buffers_.clear();
  close(fd_);
  fd_ = -1;
}

V4l2Capture::Result V4l2Capture::next(VideoFrame& frame, int timeout_ms, int wake_fd) {
  pollfd fds[2] = {{fd_, POLLIN, 0}, {wake_fd, POLLIN, 0}};
  int r;
  do r = poll(fds, wake_fd >= 0 ? 2 : 1, timeout_ms);
  while (r < 0 && errno == EINTR);
  if (r < 0) {
    error_ = errstr("poll");
    return Result::kGone;
  }
  if (wake_fd >= 0 && fds[1].revents) return Result::kWoken;
  if (r == 0) return Result::kTimeout;
  v4l2_buffer b{};
  b.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
  b.memory = V4L2_MEMORY_MMAP;
  if (xioctl(fd_, VIDIOC_DQBUF, &b) < 0) {
    if (errno == EAGAIN) {
      // POLLERR with nothing to dequeue: the device is going away.
      if (fds[0].revents & (POLLERR | POLLHUP)) {
        error_ = "the camera stopped delivering frames (unplugged?)";
        return Result::kGone;
      }
      return Result::kTimeout;
    }
    error_ = errno == ENODEV ? std::string("the camera was unplugged") : errstr("DQBUF");
    return Result::kGone;
  }
  if (b.index >= buffers_.size()) {
    error_ = "the driver returned a buffer index out of range";
    return Result::kGone;
  }
  frame.index = static_cast<int>(b.index);
  frame.data = static_cast<const uint8_t*>(buffers_[b.index].start);
  frame.bytes = std::min<size_t>(b.bytesused ? b.bytesused : buffers_[b.index].length,
                                 buffers_[b.index].length);
  frame.sequence = b.sequence;
  frame.timestamp_ns = static_cast<int64_t>(b.timestamp.tv_sec) * 1'000'000'000 +
                       static_cast<int64_t>(b.timestamp.tv_usec) * 1000;
  if (b.flags & V4L2_BUF_FLAG_ERROR) frame.bytes = 0;  // a damaged frame: caller skips it
  return Result::kFrame;
}

void V4l2Capture::release(const VideoFrame& frame) {
  if (frame.index < 0 || fd_ < 0) return;
  v4l2_buffer b{};
  b.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
  b.memory = V4L2_MEMORY_MMAP;
  b.index = static_cast<uint32_t>(frame.index);
  xioctl(fd_, VIDIOC_QBUF, &b);  // a failure shows up as kGone on the next DQBUF
}

std::vector<V4l2Control> V4l2Capture::v4l2_controls() {
  std::vector<V4l2Control> out;
  v4l2_queryctrl q{};
  q.id = V4L2_CTRL_FLAG_NEXT_CTRL;
  while (xioctl(fd_, VIDIOC_QUERYCTRL, &q) == 0) {
    const uint32_t id = q.id;
    if (!(q.flags & V4L2_CTRL_FLAG_DISABLED) &&
        (q.type == V4L2_CTRL_TYPE_INTEGER || q.type == V4L2_CTRL_TYPE_BOOLEAN ||
         q.type == V4L2_CTRL_TYPE_MENU || q.type == V4L2_CTRL_TYPE_INTEGER_MENU)) {
      V4l2Control c;
      c.id = id;
      c.name = reinterpret_cast<const char*>(q.name);
      c.type = static_cast<int>(q.type);
      c.minimum = q.minimum;
      c.maximum = q.maximum;
      c.step = q.step;
      c.default_value = q.default_value;
      c.read_only = q.flags & V4L2_CTRL_FLAG_READ_ONLY;
      c.inactive = q.flags & V4L2_CTRL_FLAG_INACTIVE;
      if (auto v = get_control(id)) {
        c.value = *v;
        out.push_back(c);
      }
    }
    q = {};
    q.id = id | V4L2_CTRL_FLAG_NEXT_CTRL;
  }
  return out;
}

std::optional<int64_t> V4l2Capture::get_control(uint32_t id) {
  v4l2_control c{};
  c.id = id;
  if (xioctl(fd_, VIDIOC_G_CTRL, &c) < 0) return std::nullopt;
  return c.value;
}

bool V4l2Capture::set_control(uint32_t id, int64_t value, std::string& why) {
  v4l2_queryctrl q{};
  q.id = id;
  if (xioctl(fd_, VIDIOC_QUERYCTRL, &q) < 0 || (q.flags & V4L2_CTRL_FLAG_DISABLED)) {
    why = "not offered by this camera";
    return false;
  }
  if (value < q.minimum || value > q.maximum) {
    why = "value " + std::to_string(value) + " outside [" + std::to_string(q.minimum) + ", " +
          std::to_string(q.maximum) + "]";
    return false;
  }
  v4l2_control c{};
  c.id = id;
  c.value = static_cast<int32_t>(value);
  if (xioctl(fd_, VIDIOC_S_CTRL, &c) < 0) {
    why = std::strerror(errno);
    return false;
  }
  return true;
}

std::vector<CaptureControl> V4l2Capture::controls() {
  std::vector<CaptureControl> out;
  for (const V4l2Control& c : v4l2_controls())
    out.push_back({c.id, c.name, std::to_string(c.value), std::to_string(c.default_value)});
  return out;
}

std::vector<LockedControl> V4l2Capture::lock_auto(const AutoLockRequest& o) {
  std::vector<LockedControl> out;
  auto set = [&](uint32_t id, int64_t v, const char* name, const std::string& what) {
    std::string why;
    out.push_back({name, set_control(id, v, why) ? what : "not set: " + why});
  };
  auto keep = [&](uint32_t id, int64_t v, const char* name) {
    if (v >= 0) {
      set(id, v, name, "set to " + std::to_string(v));
    } else if (auto cur = get_control(id)) {
      out.push_back({name, "kept at " + std::to_string(*cur)});
    } else {
      out.push_back({name, "not offered"});
    }
  };
  if (o.keep_auto) {
    out.push_back({"auto controls", "left as they were (--keep-auto)"});
    return out;
  }
  // Everything manual, at the values now in use.
  set(V4L2_CID_EXPOSURE_AUTO, V4L2_EXPOSURE_MANUAL, "exposure_auto", "manual");
  set(V4L2_CID_EXPOSURE_AUTO_PRIORITY, 0, "exposure_auto_priority", "off (constant frame rate)");
  keep(V4L2_CID_EXPOSURE_ABSOLUTE, o.exposure, "exposure_time_absolute");
  set(V4L2_CID_AUTOGAIN, 0, "gain_automatic", "off");
  keep(V4L2_CID_GAIN, o.gain, "gain");
  set(V4L2_CID_AUTO_WHITE_BALANCE, 0, "white_balance_automatic", "off");
  keep(V4L2_CID_WHITE_BALANCE_TEMPERATURE, o.white_balance, "white_balance_temperature");
  return out;
}

std::vector<std::string> find_capture_devices() {
  std::vector<std::string> out;
  DIR* d = opendir("/dev");
  if (!d) return out;
  while (dirent* e = readdir(d)) {
    if (std::strncmp(e->d_name, "video", 5) != 0) continue;
    const std::string path = std::string("/dev/") + e->d_name;
    const int fd = open(path.c_str(), O_RDWR | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) continue;
    v4l2_capability cap{};
    if (xioctl(fd, VIDIOC_QUERYCAP, &cap) == 0) {
      const uint32_t caps =
          cap.capabilities & V4L2_CAP_DEVICE_CAPS ? cap.device_caps : cap.capabilities;
      if ((caps & V4L2_CAP_VIDEO_CAPTURE) && (caps & V4L2_CAP_STREAMING)) out.push_back(path);
    }
    close(fd);
  }
  closedir(d);
  // /dev/video10 after /dev/video9.
  std::sort(out.begin(), out.end(), [](const std::string& a, const std::string& b) {
    return a.size() != b.size() ? a.size() < b.size() : a < b;
  });
  return out;
}

bool frame_to_gray(const V4l2Format& f, const uint8_t* data, size_t bytes, uint8_t* out) {
  const int bpp = bytes_per_pixel(f.fourcc);
  if (!bpp || bytes < static_cast<size_t>(f.bytesperline) * (f.height - 1) +
                          static_cast<size_t>(f.width) * bpp)
    return false;
  for (int y = 0; y < f.height; ++y) {
    const uint8_t* s = data + static_cast<size_t>(y) * f.bytesperline;
    uint8_t* d = out + static_cast<size_t>(y) * f.width;
    switch (f.fourcc) {
      case V4L2_PIX_FMT_GREY:
      case V4L2_PIX_FMT_NV12:
      case V4L2_PIX_FMT_YUV420:
        std::memcpy(d, s, static_cast<size_t>(f.width));
        break;
      case V4L2_PIX_FMT_YUYV:
        for (int x = 0; x < f.width; ++x) d[x] = s[2 * x];
        break;
      case V4L2_PIX_FMT_UYVY:
        for (int x = 0; x < f.width; ++x) d[x] = s[2 * x + 1];
        break;
      case V4L2_PIX_FMT_RGB24:
      case V4L2_PIX_FMT_BGR24: {
        const int r = f.fourcc == V4L2_PIX_FMT_RGB24 ? 0 : 2, b = 2 - r;
        // BT.601 luma, integer weights summing to 256.
        for (int x = 0; x < f.width; ++x)
          d[x] = static_cast<uint8_t>(
              (77 * s[3 * x + r] + 150 * s[3 * x + 1] + 29 * s[3 * x + b]) >> 8);
        break;
      }
    }
  }
  return true;
}

bool frame_to_rgb(const V4l2Format& f, const uint8_t* data, size_t bytes, uint8_t* out) {
  const int bpp = bytes_per_pixel(f.fourcc);
  if (!bpp || f.fourcc == V4L2_PIX_FMT_NV12 || f.fourcc == V4L2_PIX_FMT_YUV420 ||
      bytes <
          static_cast<size_t>(f.bytesperline) * (f.height - 1) + static_cast<size_t>(f.width) * bpp)
    return false;
  auto clamp8 = [](int v) { return static_cast<uint8_t>(v < 0 ? 0 : v > 255 ? 255 : v); };
  for (int y = 0; y < f.height; ++y) {
    const uint8_t* s = data + static_cast<size_t>(y) * f.bytesperline;
    uint8_t* d = out + static_cast<size_t>(y) * f.width * 3;
    for (int x = 0; x < f.width; ++x) {
      switch (f.fourcc) {
        case V4L2_PIX_FMT_GREY:
          d[3 * x] = d[3 * x + 1] = d[3 * x + 2] = s[x];
          break;
        case V4L2_PIX_FMT_RGB24:
          std::memcpy(d + 3 * x, s + 3 * x, 3);
          break;
        case V4L2_PIX_FMT_BGR24:
          d[3 * x] = s[3 * x + 2], d[3 * x + 1] = s[3 * x + 1], d[3 * x + 2] = s[3 * x];
          break;
        default: {  // YUYV / UYVY, BT.601 limited range, fixed-point
          const uint8_t* p = s + 4 * (x / 2);
          const bool yuyv = f.fourcc == V4L2_PIX_FMT_YUYV;
          const int Y = (yuyv ? p[(x & 1) * 2] : p[1 + (x & 1) * 2]) - 16;
          const int U = (yuyv ? p[1] : p[0]) - 128, V = (yuyv ? p[3] : p[2]) - 128;
          d[3 * x] = clamp8((298 * Y + 409 * V + 128) >> 8);
          d[3 * x + 1] = clamp8((298 * Y - 100 * U - 208 * V + 128) >> 8);
          d[3 * x + 2] = clamp8((298 * Y + 516 * U + 128) >> 8);
        }
      }
    }
  }
  return true;
}

}  // namespace candela
