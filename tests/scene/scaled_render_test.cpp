// A scene drawn at a reduced size scales up only where its elements draw
// (scene/scaled_render.h): the picture must be the one scaling up everything
// gives, pixel for pixel, and the part scaled up must be smaller than the
// screen where the elements leave most of it dark.
#include "scene/scaled_render.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>

#include "core/random.h"
#include "scene/scene_file.h"
#include "support/render_harness.h"
#include "support/scene_text.h"

namespace candela {
namespace {

Mat4 camera(Vec3 eye, Vec3 target, float aspect) {
  return Mat4::perspective(40.0f * 3.14159265f / 180.0f, aspect, 0.02f, 100.0f) *
         Mat4::look_at(eye, target, {0, 1, 0});
}

// Every point of the box lands inside its projected pixels.
TEST(ScaledRender, ProjectedBoxHoldsEveryPointOfTheBox) {
  const RenderSize size{640, 360};
  const Mat4 vp = camera({0.3f, 0.5f, 1.4f}, {0.0f, 0.3f, 0.0f}, 640.0f / 360.0f);
  Box3 box;
  box.add({-0.2f, 0.0f, -0.1f});
  box.add({0.25f, 0.6f, 0.15f});
  PixelBox px;
  ASSERT_TRUE(project_box(box, vp, size, px));
  EXPECT_FALSE(px.empty());
  EXPECT_LT((px.x1 - px.x0) * (px.y1 - px.y0), size.width * size.height / 2)
      << "a box a third of the view across covers well under half of it";
  Pcg32 rng(7);
  for (int i = 0; i < 2000; ++i) {
    const Vec3 p{box.lo.x + (box.hi.x - box.lo.x) * static_cast<float>(rng.unit_double()),
                 box.lo.y + (box.hi.y - box.lo.y) * static_cast<float>(rng.unit_double()),
                 box.lo.z + (box.hi.z - box.lo.z) * static_cast<float>(rng.unit_double())};
    const Vec4 c = vp * Vec4{p.x, p.y, p.z, 1.0f};
    const float x = (c.x / c.w + 1.0f) * 0.5f * size.width;
    const float y = (c.y / c.w + 1.0f) * 0.5f * size.height;
    ASSERT_GE(x, px.x0);
    ASSERT_LE(x, px.x1);
    ASSERT_GE(y, px.y0);
    ASSERT_LE(y, px.y1);
  }
}

TEST(ScaledRender, BoxReachingBehindTheCameraHasNoBound) {
  const Mat4 vp = camera({0, 0.3f, 1.0f}, {0, 0.3f, 0}, 16.0f / 9.0f);
  Box3 box;
  box.add({-0.1f, 0.2f, 0.0f});
  box.add({0.1f, 0.4f, 2.0f});  // through the camera
  PixelBox px;
  EXPECT_FALSE(project_box(box, vp, {640, 360}, px));
  // Wholly out of view: nothing to scale up.
  Box3 aside;
  aside.add({5.0f, 0.2f, 0.0f});
  aside.add({6.0f, 0.4f, 0.1f});
  ASSERT_TRUE(project_box(aside, vp, {640, 360}, px));
  EXPECT_TRUE(px.empty());
}

TEST(ScaledRender, ScaledUpBoxReachesAsFarAsTheLookup) {
  // Two reduced pixels around, doubled; clamped at the screen's edges.
  EXPECT_EQ(scaled_up_box({100, 50, 200, 150}, {960, 540}, {1920, 1080}),
            (PixelBox{196, 96, 404, 304}));
  EXPECT_EQ(scaled_up_box({0, 1, 960, 540}, {960, 540}, {1920, 1080}),
            (PixelBox{0, 0, 1920, 1080}));
  EXPECT_TRUE(scaled_up_box({}, {960, 540}, {1920, 1080}).empty());
}

double area_share(PixelBox b, int w, int h) {
  return static_cast<double>(b.x1 - b.x0) * (b.y1 - b.y0) / (static_cast<double>(w) * h);
}

// Draws `desc` at half size (kW x kH on the screen), calm and then in a
// strong steady wind, and compares each picture, scaled up only where the
// elements draw, with the whole scale-up's, byte for byte. Returns the
// largest share of the screen scaled up.
double compare_with_whole(SceneDesc desc, const char* what) {
  constexpr int kW = 640, kH = 360;
  desc.render_max_height = kH / 2;
  test::RenderHarness h(std::move(desc), kW, kH);
  double largest = 0;
  for (int round = 0; round < 4; ++round) {
    SCOPED_TRACE(std::string(what) + ", round " + std::to_string(round));
    if (round == 2)  // wind from the left: the flames bend and stretch
      h.scene().wind().push({WindEvent::Type::kSteady, Fixed::from_int(4), Fixed{}});
    h.run(round == 0 ? 30 : 90);
    h.scene().scale_up_whole(false);
    const test::Frame part = h.read();
    const PixelBox box = h.scene().last_scaled_up();
    h.scene().scale_up_whole(true);
    const test::Frame whole = h.read();
    EXPECT_EQ(h.scene().last_scaled_up(), (PixelBox{0, 0, kW, kH}));
    h.scene().scale_up_whole(false);
    largest = std::max(largest, area_share(box, kW, kH));
    int differ = 0;
    for (size_t i = 0; i < part.rgba.size(); ++i) differ += part.rgba[i] != whole.rgba[i];
    EXPECT_EQ(differ, 0) << "bytes differ from the whole scale-up";
    double lit = 0;  // something to compare: the scene is drawn
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) lit += whole.luma(x, y) > 40;
    EXPECT_GT(lit, 0.01 * kW * kH);
  }
  std::printf("%s at half size: at most %.2f of the screen scaled up\n", what, largest);
  return largest;
}

// The story fire on its embers, the built-in scene.
TEST(ScaledRenderScene, TheStoryFireIsTheSameScaledUpOnlyWhereItDraws) {
  const double largest = compare_with_whole(load_builtin_scene("eigen-story"), "eigen-story");
  // The hearth's logs and bed span three quarters of the width, the fire's
  // billboard most of the height: the rest of the screen is cleared.
  EXPECT_LT(largest, 0.8);
}

// Flames whose glow reaches their billboards' margins, one of them (Learning
// Flames' shapes, the candle model) bent by the wind, beside a hearth's logs close
// to the camera (their knobbly radius is the hearth's).
TEST(ScaledRenderScene, GlowingFlamesAndCloseLogsAreTheSameScaledUpOnlyWhereTheyDraw) {
  const double largest = compare_with_whole(
      load_scene_text("seed = 3\n" + test::black_room(0.0, 0.25, 0.9, 0.0, 0.2, 0.0, 40) + R"(
[[element]]
kind = "eigenflame"
model = "builtin:fire"
position = [-0.15, 0.0, 0.0]
height = 0.25
glow_strength = 4
glow_radius = 0.15
[[element]]
kind = "eigenflame"
driver = "arp"
position = [0.05, 0.05, 0.1]
height = 0.12
glow_strength = 3
glow_radius = 0.15
[[element]]
kind = "hearth"
position = [0.2, 0.0, 0.25]
width = 0.2
depth = 0.15
logs = 3
log_radius = 0.04
light_strength = 4
)",
                      "<test scene>"),
      "glowing flames and close logs");
  EXPECT_LT(largest, 0.8);
}

// An element that cannot say where it draws (the test pattern) leaves the
// whole picture to be scaled up.
TEST(ScaledRenderScene, AnElementThatCannotSayScalesUpEverything) {
  constexpr int kW = 320, kH = 240;
  SceneDesc desc =
      load_scene_text(test::black_room(0.0, 0.3, 1.2, 0.0, 0.2, 0.0, 40) +
                          "[display]\nrender_max_height = 120\n"
                          "[[element]]\nkind = \"hearth\"\nposition = [0, 0, 0]\nwidth = 0.3\n"
                          "[[element]]\nkind = \"test_pattern\"\n",
                      "<test scene>");
  test::RenderHarness h(std::move(desc), kW, kH);
  h.run(2);
  (void)h.read();
  EXPECT_EQ(h.scene().last_scaled_up(), (PixelBox{0, 0, kW, kH}));
}

}  // namespace
}  // namespace candela
