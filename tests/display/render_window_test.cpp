// The desktop emulator backend draws the same test pattern into a real X11
// window (run under Xvfb by ctest).
#include <gtest/gtest.h>

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
