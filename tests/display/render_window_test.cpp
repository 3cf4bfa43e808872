// The desktop emulator backend draws the same test pattern into a real X11
// window (run under Xvfb by ctest).
#include <gtest/gtest.h>

#include <cstdlib>
#include <vector>

#include "support/render_harness.h"

namespace candela {
namespace {

TEST(WindowDisplay, DrawsTheTestPatternInAWindow) {
  test::RenderHarness h(load_builtin_scene("test-pattern"), 320, 180, 0, "window");
  EXPECT_EQ(h.display().name(), "window");
  h.run(3);
  const test::Frame f = h.read();
  // Yellow bar (second eighth) and blue bar (seventh eighth).
  const auto y = f.at(320 * 3 / 16, 60);
  EXPECT_GT(y.r, 250);
  EXPECT_GT(y.g, 250);
  EXPECT_LT(y.b, 5);
  const auto b = f.at(320 * 13 / 16, 60);
  EXPECT_LT(b.r, 5);
  EXPECT_LT(b.g, 5);
  EXPECT_GT(b.b, 250);
}

}  // namespace
}  // namespace candela

namespace candela {
namespace {

// Two candles, the near one listed first: drawn in order without a depth
// buffer, the far one's (green) body would cover the near one's where they overlap.
const char* kOverlappingCandles = R"(
[background]
color = "#000000"
[camera]
position = [0.0, 0.1, 0.5]
target = [0.0, 0.08, 0.0]
fov = 40
[[element]]
kind = "candles"
[[element.candle]]
position = [0.0, 0.0, 0.1]
height = 0.12
radius = 0.03
wax = "#f0f0f0"
[[element.candle]]
position = [0.02, 0.0, -0.1]
height = 0.16
radius = 0.035
wax = "#30ff30"
)";

// The window, like the headless display, has a depth buffer: the near
// candle's white wax stays in front of the far candle's green, and the window
// shows the frame headless renders.
TEST(WindowDisplay, NearCandleHidesTheFarOneAsHeadless) {
  constexpr int w = 320, h = 240;
  std::vector<uint8_t> headless;
  {
    test::RenderHarness a(kOverlappingCandles, w, h);
    a.run(5);
    headless = a.read().rgba;
  }
  test::RenderHarness b(kOverlappingCandles, w, h, 0, "window");
  ASSERT_EQ(b.display().name(), "window");
  b.run(5);
  const test::Frame f = b.read();
  ASSERT_EQ(f.rgba.size(), headless.size());
  // Where the headless frame shows the near candle's wax (lit warm: red at
  // least green), the window shows no green.
  int wax = 0, green_instead = 0, off = 0;
  for (size_t i = 0; i + 3 < headless.size(); i += 4) {
    const int r = headless[i], g = headless[i + 1];
    if (r > 20 && r >= g) {
      ++wax;
      if (f.rgba[i + 1] > f.rgba[i] + 8) ++green_instead;
    }
    for (size_t c = 0; c < 3; ++c) off += std::abs(f.rgba[i + c] - headless[i + c]) > 8;
  }
  EXPECT_GT(wax, 500);  // the near candle is there to be hidden
  EXPECT_EQ(green_instead, 0);
  EXPECT_LT(off, static_cast<int>(headless.size() / 4) / 200);  // under 0.5% of pixels differ
}

}  // namespace
}  // namespace candela
