// The test pattern, rendered headless: bar colours, marker position, border.
#include <gtest/gtest.h>

#include "elements/test_pattern/test_pattern.h"
#include "support/render_harness.h"

namespace candela {
namespace {

constexpr int kW = 320, kH = 180;

const char* kScene = R"(
[background]
color = "#000000"
[[element]]
kind = "test_pattern"
period_steps = 120
)";

void expect_near(test::Rgba c, int r, int g, int b, int tol = 2) {
  EXPECT_NEAR(c.r, r, tol);
  EXPECT_NEAR(c.g, g, tol);
  EXPECT_NEAR(c.b, b, tol);
}

TEST(TestPattern, BarsHaveTheirColoursInOrder) {
  test::RenderHarness h(kScene, kW, kH);
  h.run(1);
  const test::Frame f = h.read();
  const int expected[8][3] = {{255, 255, 255}, {255, 255, 0}, {0, 255, 255}, {0, 255, 0},
                              {255, 0, 255},   {255, 0, 0},   {0, 0, 255},   {0, 0, 0}};
  for (int i = 0; i < 8; ++i) {
    SCOPED_TRACE(i);
    expect_near(f.at(kW * (2 * i + 1) / 16, kH / 3), expected[i][0], expected[i][1],
                expected[i][2]);
  }
}

TEST(TestPattern, MarkerMovesWithTheAnimationClock) {
  for (uint64_t frames : {16u, 31u, 61u, 91u, 121u + 45u}) {
    SCOPED_TRACE(frames);
    test::RenderHarness h(kScene, kW, kH);
    h.run(frames);
    const test::Frame f = h.read();
    // Find the white run in the marker band (y at the band's middle).
    const int y = kH * 11 / 12;
    int first = -1, last = -1;
    for (int x = 2; x < kW - 2; ++x)
      if (f.at(x, y).r > 200) {
        if (first < 0) first = x;
        last = x;
      }
    ASSERT_GE(first, 0);
    const double side = kH / 6.0 * 0.8;
    const double expected_left = test_pattern_phase(frames - 1, 120) * (kW - side);
    EXPECT_NEAR(first, expected_left, 1.5);
    EXPECT_NEAR(last - first + 1, side, 1.5);
    // The band itself is grey around the marker.
    expect_near(f.at(first > kW / 2 ? 10 : kW - 10, y), 64, 64, 64, 3);
  }
}

TEST(TestPattern, BorderIsWhiteOnEveryEdge) {
  test::RenderHarness h(kScene, kW, kH);
  h.run(1);
  const test::Frame f = h.read();
  for (int x : {0, kW / 2, kW - 1}) {
    expect_near(f.at(x, 0), 255, 255, 255);
    expect_near(f.at(x, kH - 1), 255, 255, 255);
  }
  // Inside the black bar (x in the last eighth), one pixel in: black.
  expect_near(f.at(kW - 3, kH / 3), 0, 0, 0);
}

TEST(TestPattern, SameStepsGiveTheSameFrame) {
  // One harness at a time: read() uses the current GL context.
  std::vector<uint8_t> first;
  {
    test::RenderHarness a(kScene, kW, kH);
    a.run(17);
    first = a.read().rgba;
  }
  test::RenderHarness b(kScene, kW, kH);
  b.run(17);
  EXPECT_EQ(b.read().rgba, first);
  b.run(1);  // one step later the marker has moved
  EXPECT_NE(b.read().rgba, first);
}

}  // namespace
}  // namespace candela
