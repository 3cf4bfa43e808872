// The test pattern, rendered headless: bar colours, marker position, border.
#include <gtest/gtest.h>

#include <algorithm>
#include <iterator>
#include <string>

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

// The eight colour bars, left to right, sampled in the middle of each.
void expect_bars_in_order(const test::Frame& f) {
  const int expected[8][3] = {{255, 255, 255}, {255, 255, 0}, {0, 255, 255}, {0, 255, 0},
                              {255, 0, 255},   {255, 0, 0},   {0, 0, 255},   {0, 0, 0}};
  for (int i = 0; i < 8; ++i) {
    SCOPED_TRACE(i);
    expect_near(f.at(kW * (2 * i + 1) / 16, kH / 3), expected[i][0], expected[i][1],
                expected[i][2]);
  }
}

TEST(TestPattern, BarsHaveTheirColoursInOrder) {
  test::RenderHarness h(kScene, kW, kH);
  h.run(1);
  const test::Frame f = h.read();
  expect_bars_in_order(f);
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

// Reads the counter band's eight seven-segment digits (the shader's layout:
// cells 0.7 of the band high, 0.55 as wide, 1.3 widths apart), by sampling
// each segment's middle; -1 for a cell that is no digit.
std::string read_counter(const test::Frame& f, int h) {
  static constexpr int kMask[10] = {0x3F, 0x06, 0x5B, 0x4F, 0x66, 0x6D, 0x7D, 0x07, 0x7F, 0x6F};
  // Segment a..g middles, cell-local (x right, y down).
  static constexpr double kAt[7][2] = {{0.5, 0.07},  {0.93, 0.25}, {0.93, 0.75}, {0.5, 0.93},
                                       {0.07, 0.75}, {0.07, 0.25}, {0.5, 0.5}};
  const double band = h / 6.0, ch = band * 0.7, cw = ch * 0.55;
  std::string out;
  for (int cell = 0; cell < 8; ++cell) {
    int mask = 0;
    for (int s = 0; s < 7; ++s) {
      const double x = band * 0.15 + cell * cw * 1.3 + kAt[s][0] * cw;
      const double y = h * 2.0 / 3.0 + band * 0.15 + kAt[s][1] * ch;
      if (f.at(static_cast<int>(x), static_cast<int>(y)).r > 128) mask |= 1 << s;
    }
    const int* d = std::find(std::begin(kMask), std::end(kMask), mask);
    out += d == std::end(kMask) ? '?' : static_cast<char>('0' + (d - kMask));
  }
  return out;
}

TEST(TestPattern, CounterShowsTheFramesPresented) {
  // Large enough that each segment is several pixels thick.
  constexpr int w = 640, h = 360;
  test::RenderHarness pattern(kScene, w, h);
  pattern.run(1);  // the first frame: none presented before it
  EXPECT_EQ(read_counter(pattern.read(), h), "00000000");
  pattern.run(128);
  EXPECT_EQ(read_counter(pattern.read(), h), "00000128");
}

// [display] render_scale: the scene is drawn at half the size and scaled up
// to fill the screen. The pattern's one-pixel border, drawn in the half-size
// target, covers two screen pixels; the bars are where they were.
TEST(TestPattern, ReducedRenderSizeFillsTheScreen) {
  const std::string half = std::string("[display]\nrender_scale = 0.5\n") + kScene;
  test::RenderHarness h(half, kW, kH);
  h.run(1);
  const test::Frame f = h.read();
  ASSERT_EQ(f.width, kW);
  ASSERT_EQ(f.height, kH);
  // Inside the black bar, one pixel in from the right edge: the border's
  // second screen pixel (a full-size frame has black there, see below).
  EXPECT_GT(f.at(kW - 2, kH / 3).r, 150);
  EXPECT_LT(f.at(kW - 5, kH / 3).r, 20);
  expect_bars_in_order(f);
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
