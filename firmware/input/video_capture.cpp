#include "input/video_capture.h"

#include <linux/videodev2.h>

#include "core/error.h"
#include "core/log.h"
#include "input/v4l2_capture.h"
#ifdef CANDELA_HAVE_LIBCAMERA
#include "input/libcamera_capture.h"
#endif

namespace candela {
namespace {

// DRM fourccs (what libcamera's PixelFormat holds) are little-endian words:
// DRM "BGR888" stores R, G, B in memory, which V4L2 calls RGB24 ('RGB3').
constexpr uint32_t drm_fourcc(char a, char b, char c, char d) {
  return static_cast<uint32_t>(a) | static_cast<uint32_t>(b) << 8 | static_cast<uint32_t>(c) << 16 |
         static_cast<uint32_t>(d) << 24;
}

struct FormatPair {
  uint32_t drm, v4l2;
};
constexpr FormatPair kFormats[] = {
    {drm_fourcc('R', '8', ' ', ' '), V4L2_PIX_FMT_GREY},
    {drm_fourcc('Y', 'U', 'Y', 'V'), V4L2_PIX_FMT_YUYV},
    {drm_fourcc('U', 'Y', 'V', 'Y'), V4L2_PIX_FMT_UYVY},
    {drm_fourcc('N', 'V', '1', '2'), V4L2_PIX_FMT_NV12},
    {drm_fourcc('Y', 'U', '1', '2'), V4L2_PIX_FMT_YUV420},
    {drm_fourcc('B', 'G', '2', '4'), V4L2_PIX_FMT_RGB24},  // DRM BGR888
    {drm_fourcc('R', 'G', '2', '4'), V4L2_PIX_FMT_BGR24},  // DRM RGB888
};

bool is_dev_path(const std::string& d) { return d.rfind("/dev/", 0) == 0; }

std::unique_ptr<VideoCapture> open_v4l2(const CaptureSettings& s) {
  CaptureSettings v = s;
  if (v.device == "auto") {
    const auto found = find_capture_devices();
    if (found.empty()) throw RuntimeError("no camera found (no V4L2 capture device in /dev)");
    v.device = found.front();
  }
  return std::make_unique<V4l2Capture>(v);
}

std::unique_ptr<VideoCapture> open_libcamera(const CaptureSettings& s) {
#ifdef CANDELA_HAVE_LIBCAMERA
  return open_libcamera_capture(s);
#else
  (void)s;
  throw RuntimeError(
      "the libcamera backend is not built into this candela (install libcamera-dev and "
      "rebuild); use backend \"v4l2\"");
#endif
}

}  // namespace

std::string VideoCapture::name() const { return device() + " (" + card() + ") via " + backend(); }

bool libcamera_available() {
#ifdef CANDELA_HAVE_LIBCAMERA
  return true;
#else
  return false;
#endif
}

uint32_t v4l2_fourcc_from_libcamera(uint32_t drm) {
  for (const FormatPair& p : kFormats)
    if (p.drm == drm) return p.v4l2;
  return 0;
}

uint32_t libcamera_fourcc_from_v4l2(uint32_t v4l2) {
  for (const FormatPair& p : kFormats)
    if (p.v4l2 == v4l2) return p.drm;
  return 0;
}

std::unique_ptr<VideoCapture> open_video_capture(const std::string& backend,
                                                 const CaptureSettings& s) {
  if (backend == "v4l2") return open_v4l2(s);
  if (backend == "libcamera") {
    if (is_dev_path(s.device))
      throw RuntimeError("libcamera: " + s.device +
                         " is a device node; libcamera wants a camera id (see `cam -l`) or "
                         "\"auto\"");
    return open_libcamera(s);
  }
  if (backend != "auto")
    throw RuntimeError("camera backend \"" + backend + "\": expected v4l2, libcamera or auto");
  if (is_dev_path(s.device)) return open_v4l2(s);  // a V4L2 node is V4L2's, whatever is built
  // rpicam-apps style: libcamera first (Pi cameras need it), plain V4L2 next.
  std::string why;
  if (libcamera_available()) {
    try {
      auto cap = open_libcamera(s);
      LOG_INFO("camera backend auto: libcamera, %s", cap->name().c_str());
      return cap;
    } catch (const std::exception& e) {
      why = e.what();
    }
  } else {
    why = "libcamera is not built in";
  }
  if (s.device != "auto")  // a camera id only libcamera knows
    throw RuntimeError(why);
  try {
    auto cap = open_v4l2(s);
    LOG_INFO("camera backend auto: V4L2, %s (libcamera: %s)", cap->name().c_str(), why.c_str());
    return cap;
  } catch (const std::exception& e) {
    throw RuntimeError(std::string(e.what()) + "; libcamera: " + why);
  }
}

}  // namespace candela
