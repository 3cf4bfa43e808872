// The live preview on real EGL (Mesa's surfaceless platform here): the image
// it presents is the frame it was given, letterboxed; a preview that cannot
// open stays out of the recording's way.
#include "preview.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "core/image.h"

namespace candela::record {
namespace {

namespace fs = std::filesystem;

std::string scratch(const std::string& name) {
  const fs::path dir = fs::path(CANDELA_BINARY_DIR) / "test-scratch" /
                       ("record_preview_" + name + "_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir.string();
}

// A frame no flip, transpose or channel swap leaves unchanged.
std::vector<uint8_t> ramp_frame(int w, int h, int channels) {
  std::vector<uint8_t> f(static_cast<size_t>(w) * h * channels);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < channels; ++c)
        f[(static_cast<size_t>(y) * w + x) * channels + c] =
            static_cast<uint8_t>(channels == 1 ? 20 + 150 * x / (w - 1) + 70 * y / (h - 1)
                                 : c == 0      ? 20 + 200 * x / (w - 1)
                                 : c == 1      ? 20 + 200 * y / (h - 1)
                                               : 60);
  return f;
}

// Bilinear sample of frame channel c at frame coordinates (u, v) (texel centres at +0.5).
double sample(const std::vector<uint8_t>& f, int w, int h, int channels, double u, double v,
              int c) {
  const double x = std::clamp(u - 0.5, 0.0, w - 1.0), y = std::clamp(v - 0.5, 0.0, h - 1.0);
  const int x0 = static_cast<int>(x), y0 = static_cast<int>(y);
  const int x1 = std::min(x0 + 1, w - 1), y1 = std::min(y0 + 1, h - 1);
  const double fx = x - x0, fy = y - y0;
  auto at = [&](int xx, int yy) {
    return static_cast<double>(f[(static_cast<size_t>(yy) * w + xx) * channels + c]);
  };
  return (at(x0, y0) * (1 - fx) + at(x1, y0) * fx) * (1 - fy) +
         (at(x0, y1) * (1 - fx) + at(x1, y1) * fx) * fy;
}

struct Compared {
  double worst_inside = 0;  // largest |shown - expected| inside the picture
  int bright_outside = 0;   // letterbox bars that are not black
  int dot_red = 0;          // red indicator pixels
};

// Compares the dumped preview with the frame as the preview should draw it.
Compared compare(const Image& shown, const std::vector<uint8_t>& frame, int fw, int fh,
                 int channels) {
  Compared r;
  const PreviewRect box = letterbox(fw, fh, shown.width, shown.height);
  const PreviewRect dot = recording_dot(shown.width, shown.height);
  for (int y = 0; y < shown.height; ++y)
    for (int x = 0; x < shown.width; ++x) {
      const bool in_dot =
          x >= dot.x && x < dot.x + dot.width && y >= dot.y && y < dot.y + dot.height;
      if (in_dot) {
        r.dot_red += shown.at(x, y, 0) > 200 && shown.at(x, y, 1) < 40;
        continue;
      }
      const bool inside =
          x >= box.x && x < box.x + box.width && y >= box.y && y < box.y + box.height;
      if (!inside) {
        r.bright_outside += shown.at(x, y, 0) + shown.at(x, y, 1) + shown.at(x, y, 2) > 0;
        continue;
      }
      const double u = (x - box.x + 0.5) * fw / box.width, v = (y - box.y + 0.5) * fh / box.height;
      for (int c = 0; c < 3; ++c) {
        const double want = sample(frame, fw, fh, channels, u, v, channels == 1 ? 0 : c);
        r.worst_inside = std::max(r.worst_inside, std::abs(shown.at(x, y, c) - want));
      }
    }
  return r;
}

TEST(RecordPreview, LetterboxKeepsTheAspect) {
  const PreviewRect wide = letterbox(320, 180, 160, 120);  // bars above and below
  EXPECT_EQ(wide.x, 0);
  EXPECT_EQ(wide.width, 160);
  EXPECT_EQ(wide.height, 90);
  EXPECT_EQ(wide.y, 15);
  const PreviewRect tall = letterbox(640, 480, 1920, 1080);  // bars left and right
  EXPECT_EQ(tall.height, 1080);
  EXPECT_EQ(tall.width, 1440);
  EXPECT_EQ(tall.x, 240);
}

TEST(RecordPreview, HeadlessShowsTheLastGrayFrameLetterboxed) {
  const std::string dir = scratch("gray");
  PreviewOptions o;
  o.mode = "headless";
  o.width = 200;
  o.height = 150;
  o.dump_dir = dir;
  RecordPreview preview(o, nullptr);
  const int fw = 320, fh = 180;
  preview.start(fw, fh, 1);
  const std::vector<uint8_t> older(static_cast<size_t>(fw) * fh, 255), ramp = ramp_frame(fw, fh, 1);
  preview.push(older.data(), 6);
  preview.push(ramp.data(), 7);  // the newest frame is the one to show
  ASSERT_TRUE(preview.wait_until_open()) << preview.error();
  preview.stop();
  EXPECT_EQ(preview.backend(), "headless");
  EXPECT_GE(preview.shown(), 1u);
  EXPECT_EQ(preview.offered(), 2u);
  EXPECT_NE(preview.manifest_json().find("\"last_sequence\":7"), std::string::npos)
      << preview.manifest_json();
  const Image shown = read_png(dir + "/preview.png", 3);
  ASSERT_EQ(shown.width, 200);
  ASSERT_EQ(shown.height, 150);
  const Compared c = compare(shown, ramp, fw, fh, 1);
  EXPECT_LE(c.worst_inside, 3.0);
  EXPECT_EQ(c.bright_outside, 0);
  const PreviewRect dot = recording_dot(200, 150);
  EXPECT_EQ(c.dot_red, dot.width * dot.height);
}

TEST(RecordPreview, HeadlessShowsRgbFramesInTheirColours) {
  const std::string dir = scratch("rgb");
  PreviewOptions o;
  o.mode = "headless";
  o.width = 256;
  o.height = 256;
  o.dump_dir = dir;
  RecordPreview preview(o, nullptr);
  const int fw = 64, fh = 48;
  preview.start(fw, fh, 3);
  const std::vector<uint8_t> ramp = ramp_frame(fw, fh, 3);
  preview.push(ramp.data(), 1);
  preview.stop();
  ASSERT_EQ(preview.backend(), "headless") << preview.error();
  const Image shown = read_png(dir + "/preview.png", 3);
  const Compared c = compare(shown, ramp, fw, fh, 3);
  EXPECT_LE(c.worst_inside, 3.0);
  EXPECT_EQ(c.bright_outside, 0);
}

TEST(RecordPreview, WindowWithoutAnXDisplayFailsClearlyAndNeverStopsTheRecording) {
  const char* saved = std::getenv("DISPLAY");
  const std::string saved_display = saved ? saved : "";
  unsetenv("DISPLAY");
  PreviewOptions o;
  o.mode = "window";
  RecordPreview preview(o, nullptr);
  preview.start(64, 48, 1);
  EXPECT_FALSE(preview.wait_until_open());
  EXPECT_NE(preview.error().find("DISPLAY"), std::string::npos) << preview.error();
  // A failed preview takes no more frames and does not ask the recording to stop.
  const std::vector<uint8_t> frame(64 * 48, 128);
  for (uint32_t i = 0; i < 100; ++i) preview.push(frame.data(), i);
  preview.stop();
  EXPECT_FALSE(preview.quit_requested());
  EXPECT_EQ(preview.shown(), 0u);
  EXPECT_EQ(preview.offered(), 100u);
  EXPECT_NE(preview.manifest_json().find("\"opened\":false"), std::string::npos);
  EXPECT_NE(preview.summary().find("DISPLAY"), std::string::npos) << preview.summary();
  if (saved) setenv("DISPLAY", saved_display.c_str(), 1);
}

TEST(RecordPreview, AutoPicksAWindowOnlyWithADisplay) {
  EXPECT_EQ(choose_preview("auto", ":0").backends, (std::vector<std::string>{"window", "drm"}));
  EXPECT_EQ(choose_preview("auto", nullptr).backends, (std::vector<std::string>{"drm"}));
  EXPECT_EQ(choose_preview("auto", "").backends, (std::vector<std::string>{"drm"}));
  EXPECT_TRUE(choose_preview("off", ":0").backends.empty());
  EXPECT_THROW(choose_preview("fb", nullptr), std::invalid_argument);
}

}  // namespace
}  // namespace candela::record
