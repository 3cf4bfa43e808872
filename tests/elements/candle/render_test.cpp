// Candles rendered headless and checked the way a viewer would: flames sit
// above their wicks, glows light the air around them, every candle shows,
// blowing them out leaves the screen dark and they come back, and the same
// seed draws the same frames.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "input/key_input.h"
#include "support/render_harness.h"
#include "support/scene_text.h"

namespace candela {
namespace {

constexpr int kW = 320, kH = 240;
constexpr float kCandleHeight = 0.08f, kRadius = 0.022f, kFlameHeight = 0.055f;
const Vec3 kCamera{0.0f, 0.09f, 0.6f}, kTarget{0.0f, 0.09f, 0.0f};

std::string scene(int candles, double glow_strength = 0.55, const std::string& extra = "") {
  std::string s = test::black_room(0.0, 0.09, 0.6, 0.0, 0.09, 0.0, 35) + R"(
[[element]]
kind = "candles"
flame_height = 0.055
glow_strength = )" +
                  std::to_string(glow_strength) + "\n" + extra + "\n";
  for (int i = 0; i < candles; ++i) {
    const double x = (i - (candles - 1) / 2.0) * 0.1;
    s += "[[element.candle]]\nposition = [" + std::to_string(x) +
         ", 0.0, 0.0]\nheight = 0.08\nradius = 0.022\n";
  }
  return s;
}

// Where a world point lands on the frame (x right, y down), as Scene draws it.
Vec2 project(Vec3 p) {
  const Mat4 view = Mat4::look_at(kCamera, kTarget, {0, 1, 0});
  const Mat4 proj =
      Mat4::perspective(35 * 3.14159265f / 180, static_cast<float>(kW) / kH, 0.02f, 100);
  const Vec4 c = (proj * view) * Vec4{p.x, p.y, p.z, 1};
  return {(c.x / c.w + 1) * 0.5f * kW, (1 - c.y / c.w) * 0.5f * kH};
}

TEST(CandleRender, FlamesStandAboveTheirWicks) {
  test::RenderHarness h(scene(3), kW, kH, 4);
  h.run(30);
  const test::Frame f = h.read();
  const float pool_top = kCandleHeight - 0.15f * kRadius;
  for (int i = 0; i < 3; ++i) {
    SCOPED_TRACE(i);
    const float x = (i - 1) * 0.1f;
    const Vec2 wick = project({x, pool_top, 0});
    const Vec2 tip = project({x, pool_top + kFlameHeight, 0});
    const float flame_px = wick.y - tip.y;
    ASSERT_GT(flame_px, 15);
    // The brightest pixel near the candle's axis.
    double best = -1;
    int bx = 0, by = 0;
    for (int y = 0; y < kH; ++y)
      for (int px = static_cast<int>(wick.x) - 8; px <= static_cast<int>(wick.x) + 8; ++px)
        if (f.luma(px, y) > best) best = f.luma(px, y), bx = px, by = y;
    EXPECT_GT(best, 200);
    EXPECT_NEAR(bx, wick.x, 4);
    // Above the wick, within the flame's height.
    EXPECT_LT(by, wick.y - 0.1f * flame_px);
    EXPECT_GT(by, wick.y - 0.9f * flame_px);
    // The wax just below the pool is lit but far dimmer than the flame.
    const Vec2 side = project({x, kCandleHeight - 0.02f, kRadius});
    EXPECT_LT(f.luma(static_cast<int>(side.x), static_cast<int>(side.y)), best * 0.8);
  }
}

// Renders a scene and reads its last frame. One harness at a time: read()
// reads whichever GL context is current, which is the newest harness's.
test::Frame render(const std::string& toml, uint64_t seed, int frames) {
  test::RenderHarness h(toml, kW, kH, seed);
  h.run(frames);
  return h.read();
}

TEST(CandleRender, GlowLightsTheAirAroundTheFlame) {
  const test::Frame a = render(scene(1), 4, 20), b = render(scene(1, 0.0), 4, 20);
  const float pool_top = kCandleHeight - 0.15f * kRadius;
  const Vec2 centre = project({0, pool_top + 0.45f * kFlameHeight, 0});
  const Vec2 beside = project({0.035f, pool_top + 0.45f * kFlameHeight, 0});
  const Vec2 above = project({0, pool_top + 1.2f * kFlameHeight, 0});
  const Vec2 far = project({0.2f, pool_top, 0});
  auto luma = [](const test::Frame& f, Vec2 p) {
    return f.luma(static_cast<int>(p.x), static_cast<int>(p.y));
  };
  // Outside the flame the glow is all there is: lit with it, dark without.
  EXPECT_GT(luma(a, beside), 12);
  EXPECT_LT(luma(b, beside), 3);
  EXPECT_GT(luma(a, above), 3);
  EXPECT_GT(luma(a, beside), luma(a, above));  // centred on the flame, fading outward
  EXPECT_LT(luma(a, far), 2);
  // The glow is centred on the flame (which sways a little): about as bright
  // on both sides.
  const Vec2 left = project({-0.035f, pool_top + 0.45f * kFlameHeight, 0});
  EXPECT_NEAR(luma(a, left), luma(a, beside), 0.35 * luma(a, beside));
  EXPECT_GT(luma(a, centre), 200);
}

TEST(CandleRender, EveryCandleShows) {
  for (int n : {1, 3, 5}) {
    SCOPED_TRACE(n);
    EXPECT_EQ(render(scene(n), 2, 10).regions_above(180), n);
  }
}

TEST(CandleRender, BlownOutThenRelit) {
  test::RenderHarness h(scene(3, 0.55, "[element.extinguish]\nrelight_seconds = 1.5\n"), kW, kH, 3);
  h.run(5);
  ASSERT_EQ(h.read().regions_above(180), 3);
  h.scene().wind().push(*key_wind_event(Key::kBlowOut, h.scene().wind().spec()));
  LoopSettings one;
  one.max_frames = 1;
  int fewest = 3, dark_frames = 0;
  for (int i = 0; i < 60 * 5; ++i) {
    run_frame_loop(h.display(), h.scene(), one);
    if (i % 5) continue;
    const int n = h.read().regions_above(180);
    fewest = std::min(fewest, n);
    dark_frames += n == 0;
  }
  EXPECT_EQ(fewest, 0);
  EXPECT_GT(dark_frames, 3);
  EXPECT_EQ(h.read().regions_above(180), 3);
}

// A candle blown out leaves a wisp of smoke above its wick that rises and
// fades within smoke_seconds (2.5 s by default), after the flame has gone.
TEST(CandleRender, BlownOutCandleSmokesThenClears) {
  test::RenderHarness h(scene(1, 0.0, "[element.extinguish]\nrelight_seconds = 8\n"), kW, kH, 3);
  h.run(5);
  h.scene().wind().push(*key_wind_event(Key::kBlowOut, h.scene().wind().spec()));
  LoopSettings one;
  one.max_frames = 1;
  // The air above the candle's top, where the flame was and the smoke rises.
  const Vec2 top = project({0, 0.08f, 0}), high = project({0, 0.2f, 0});
  auto light_above = [&](double* brightest) {
    const test::Frame f = h.read();
    double sum = 0;
    *brightest = 0;
    for (int y = static_cast<int>(high.y); y < static_cast<int>(top.y); ++y)
      for (int x = static_cast<int>(top.x) - 30; x < static_cast<int>(top.x) + 30; ++x) {
        sum += f.luma(x, y);
        *brightest = std::max(*brightest, f.luma(x, y));
      }
    return sum;
  };
  double smoke_peak = 0, last = 0;
  bool flame_gone = false;
  for (int i = 0; i < 60 * 4; ++i) {
    run_frame_loop(h.display(), h.scene(), one);
    if (i % 15) continue;
    double brightest = 0;
    last = light_above(&brightest);
    if (brightest < 120 && !flame_gone) {
      flame_gone = true;
      continue;  // the flame's last light, not smoke yet
    }
    if (flame_gone) smoke_peak = std::max(smoke_peak, last);
  }
  ASSERT_TRUE(flame_gone);
  EXPECT_GT(smoke_peak, 4 * last) << "no smoke rose after the flame went out";
  EXPECT_LT(last, 0.1 * smoke_peak) << "the smoke did not clear";
}

TEST(CandleRender, SameSeedSameFrames) {
  const std::string s = scene(3);
  const test::Frame a = render(s, 8, 45), b = render(s, 8, 45), c = render(s, 9, 45);
  EXPECT_EQ(a.rgba, b.rgba);
  EXPECT_NE(a.rgba, c.rgba);
}

}  // namespace
}  // namespace candela
