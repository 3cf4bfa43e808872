// The capture interface without a camera: libcamera's pixel formats map onto
// the V4L2 layouts the frame converters read (byte order included), and the
// factory's refusals say what is wrong.
#include "input/video_capture.h"

#include <gtest/gtest.h>
#include <linux/videodev2.h>

#include <cstring>
#include <string>
#include <vector>

#include "input/v4l2_capture.h"

namespace candela {
namespace {

constexpr uint32_t drm(const char* s) {
  return static_cast<uint32_t>(s[0]) | static_cast<uint32_t>(s[1]) << 8 |
         static_cast<uint32_t>(s[2]) << 16 | static_cast<uint32_t>(s[3]) << 24;
}

TEST(LibcameraFormats, MapToV4l2Layouts) {
  EXPECT_EQ(v4l2_fourcc_from_libcamera(drm("R8  ")), V4L2_PIX_FMT_GREY);
  EXPECT_EQ(v4l2_fourcc_from_libcamera(drm("YUYV")), V4L2_PIX_FMT_YUYV);
  EXPECT_EQ(v4l2_fourcc_from_libcamera(drm("UYVY")), V4L2_PIX_FMT_UYVY);
  EXPECT_EQ(v4l2_fourcc_from_libcamera(drm("NV12")), V4L2_PIX_FMT_NV12);
  EXPECT_EQ(v4l2_fourcc_from_libcamera(drm("YU12")), V4L2_PIX_FMT_YUV420);
  // DRM names packed words from the top: BGR888 is R, G, B in memory = V4L2 RGB24.
  EXPECT_EQ(v4l2_fourcc_from_libcamera(drm("BG24")), V4L2_PIX_FMT_RGB24);
  EXPECT_EQ(v4l2_fourcc_from_libcamera(drm("RG24")), V4L2_PIX_FMT_BGR24);
  // Bayer and 32-bit RGB: not read by candela.
  EXPECT_EQ(v4l2_fourcc_from_libcamera(drm("BA81")), 0u);
  EXPECT_EQ(v4l2_fourcc_from_libcamera(drm("XR24")), 0u);
  for (uint32_t f : {V4L2_PIX_FMT_GREY, V4L2_PIX_FMT_YUYV, V4L2_PIX_FMT_UYVY, V4L2_PIX_FMT_NV12,
                     V4L2_PIX_FMT_YUV420, V4L2_PIX_FMT_RGB24, V4L2_PIX_FMT_BGR24}) {
    EXPECT_TRUE(is_supported_format(f)) << fourcc_name(f);
    EXPECT_EQ(v4l2_fourcc_from_libcamera(libcamera_fourcc_from_v4l2(f)), f) << fourcc_name(f);
  }
  EXPECT_EQ(libcamera_fourcc_from_v4l2(V4L2_PIX_FMT_MJPEG), 0u);
}

// A pure red and a pure blue pixel as libcamera's BGR888 and RGB888 lay them
// out in memory (little-endian 24-bit words): the colours must survive.
TEST(LibcameraFormats, PackedRgbByteOrder) {
  struct Case {
    const char* drm;
    std::vector<uint8_t> bytes;  // red pixel, blue pixel
  };
  for (const Case& c :
       {Case{"BG24", {255, 0, 0, 0, 0, 255}}, Case{"RG24", {0, 0, 255, 255, 0, 0}}}) {
    VideoFormat f;
    f.fourcc = v4l2_fourcc_from_libcamera(drm(c.drm));
    f.width = 2;
    f.height = 1;
    f.bytesperline = 6;
    f.sizeimage = 6;
    uint8_t rgb[6] = {}, gray[2] = {};
    ASSERT_TRUE(frame_to_rgb(f, c.bytes.data(), c.bytes.size(), rgb)) << c.drm;
    EXPECT_EQ(std::vector<uint8_t>(rgb, rgb + 6), (std::vector<uint8_t>{255, 0, 0, 0, 0, 255}))
        << c.drm;
    ASSERT_TRUE(frame_to_gray(f, c.bytes.data(), c.bytes.size(), gray));
    EXPECT_GT(gray[0], gray[1]) << c.drm << ": red is brighter than blue in BT.601 luma";
  }
}

std::string open_error(const std::string& backend, const std::string& device) {
  CaptureSettings s;
  s.device = device;
  try {
    open_video_capture(backend, s);
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

TEST(OpenVideoCapture, RefusalsSayWhy) {
  EXPECT_NE(open_error("gphoto", "auto").find("expected v4l2, libcamera or auto"),
            std::string::npos);
  EXPECT_NE(open_error("libcamera", "/dev/video0").find("camera id"), std::string::npos);
  const std::string v4l2 = open_error("v4l2", "/dev/video62");
  EXPECT_NE(v4l2.find("/dev/video62"), std::string::npos) << v4l2;
  EXPECT_NE(v4l2.find("No such file"), std::string::npos) << v4l2;
  // auto with a /dev path: V4L2 only, whatever is built.
  EXPECT_EQ(open_error("auto", "/dev/video62"), v4l2);
}

// Really starts libcamera's CameraManager (twice: it must come and go cleanly)
// and asks for a camera no machine has.
TEST(OpenVideoCapture, LibcameraUnknownCamera) {
  for (int i = 0; i < 2; ++i) {
    const std::string e = open_error("libcamera", "candela-test/no-such-camera");
    if (libcamera_available()) {
      EXPECT_NE(e.find("no camera \"candela-test/no-such-camera\""), std::string::npos) << e;
    } else {
      EXPECT_NE(e.find("not built"), std::string::npos) << e;
    }
  }
}

}  // namespace
}  // namespace candela
