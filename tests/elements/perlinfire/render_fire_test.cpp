// The Perlin fire rendered headless: where light falls, where it must not,
// seeds, wind, and what a broken setting says.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "core/error.h"
#include "embedded_scenes.h"
#include "gl/math.h"
#include "scene/scene_file.h"
#include "support/correlation.h"
#include "support/render_harness.h"
#include "support/scene_text.h"

namespace candela {
namespace {

constexpr int kW = 96, kH = 128;
const Vec3 kCamera{0.0f, 0.35f, 1.6f}, kTarget{0.0f, 0.3f, 0.0f};
const Vec3 kPosition{0.0f, 0.0f, 0.0f}, kSize{0.45f, 0.6f, 0.45f};

std::string scene(const std::string& extra, const std::string& noise = "flow3d",
                  const std::string& head = "",
                  const std::string& quality = "steps = 12\noctaves = 3\n") {
  return head + test::black_room(0.0, 0.35, 1.6, 0.0, 0.3, 0.0, 40) + R"(
[[element]]
kind = "perlinfire"
position = [0.0, 0.0, 0.0]
size = [0.45, 0.6, 0.45]
noise = ")" +
         noise + "\"\n" + quality + extra;
}

// Where a point of the scene lands on screen (pixels, y down), as Scene draws it.
Vec2 project(Vec3 p) {
  const Mat4 vp =
      Mat4::perspective(40.0f * 3.14159265f / 180.0f, static_cast<float>(kW) / kH, 0.02f, 100.0f) *
      Mat4::look_at(kCamera, kTarget, {0, 1, 0});
  const Vec4 c = vp * Vec4{p.x, p.y, p.z, 1.0f};
  return {(c.x / c.w * 0.5f + 0.5f) * kW, (0.5f - c.y / c.w * 0.5f) * kH};
}

double mean_luma(const test::Frame& f, Vec2 at, int radius) {
  const int x = static_cast<int>(at.x), y = static_cast<int>(at.y);
  return f.mean_luma(x - radius, y - radius, x + radius + 1, y + radius + 1);
}

// Renders `frames` frames of a scene and returns the last. One harness at a
// time: each owns the current GL context while it lives.
test::Frame render(const std::string& toml, int frames, uint64_t seed = 0, bool timed = false) {
  test::RenderHarness h(toml, kW, kH, seed);
  h.time_frames(timed);
  h.run(static_cast<uint64_t>(frames));
  return h.read();
}

class FireByNoise : public ::testing::TestWithParam<const char*> {};

TEST_P(FireByNoise, BrighterAtTheBottomCentreThanAtTheTopEdge) {
  test::RenderHarness h(scene("", GetParam()), kW, kH);
  double bottom = 0, top = 0;
  for (int frames : {3, 20}) {
    h.run(static_cast<uint64_t>(frames));
    const test::Frame f = h.read();
    bottom += mean_luma(f, project({0.0f, 0.1f * kSize.y, 0.0f}), 1);
    top += mean_luma(f, project({0.0f, 0.97f * kSize.y, 0.0f}), 1);
  }
  EXPECT_GT(bottom / 2, 60.0);
  EXPECT_LT(top / 2, bottom / 2 * 0.25);
}

INSTANTIATE_TEST_SUITE_P(Kinds, FireByNoise,
                         ::testing::Values("simplex3d", "flow3d", "simplex4d", "perlin4d"));

// The box's corners on screen, widened by `margin` pixels.
void box_rect(int margin, int r[4]) {
  float x0 = 1e9f, y0 = 1e9f, x1 = -1e9f, y1 = -1e9f;
  for (int c = 0; c < 8; ++c) {
    const Vec3 p{kPosition.x + ((c & 1) ? 0.5f : -0.5f) * kSize.x, (c & 2) ? kSize.y : 0.0f,
                 kPosition.z + ((c & 4) ? 0.5f : -0.5f) * kSize.z};
    const Vec2 s = project(p);
    x0 = std::min(x0, s.x), x1 = std::max(x1, s.x), y0 = std::min(y0, s.y), y1 = std::max(y1, s.y);
  }
  r[0] = static_cast<int>(x0) - margin, r[1] = static_cast<int>(y0) - margin;
  r[2] = static_cast<int>(x1) + margin, r[3] = static_cast<int>(y1) + margin;
}

TEST(PerlinFire, NothingIsDrawnOutsideTheVolume) {
  for (const char* scale : {"1.0", "0.5"}) {
    SCOPED_TRACE(scale);
    test::RenderHarness h(scene(std::string("render_scale = ") + scale), kW, kH);
    h.run(8);
    const test::Frame f = h.read();
    int r[4];
    box_rect(2, r);
    int lit_inside = 0, lit_outside = 0;
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) {
        const bool inside = x >= r[0] && x <= r[2] && y >= r[1] && y <= r[3];
        const test::Rgba c = f.at(x, y);
        const bool lit = c.r + c.g + c.b > 0;
        (inside ? lit_inside : lit_outside) += lit;
      }
    EXPECT_EQ(lit_outside, 0);
    EXPECT_GT(lit_inside, (r[2] - r[0]) * (r[3] - r[1]) / 8);  // and there is a fire
  }
}

TEST(PerlinFire, OneSeedGivesTheSameFramesTwoSeedsDifferent) {
  const std::string s = scene("render_scale = 0.5");
  const test::Frame fa = render(s, 6, 11), fb = render(s, 6, 11), fc = render(s, 6, 12);
  EXPECT_EQ(fa.rgba, fb.rgba);
  int differ = 0;
  for (size_t i = 0; i < fa.rgba.size(); i += 4)
    differ += std::abs(fa.rgba[i] - fc.rgba[i]) + std::abs(fa.rgba[i + 1] - fc.rgba[i + 1]) > 8;
  EXPECT_GT(differ, 200);
}

TEST(PerlinFire, AnimatesOverTime) {
  test::RenderHarness h(scene(""), kW, kH);
  h.run(5);
  const test::Frame f1 = h.read();
  h.run(15);
  const test::Frame f2 = h.read();
  int differ = 0;
  for (size_t i = 0; i < f1.rgba.size(); i += 4) differ += std::abs(f1.rgba[i] - f2.rgba[i]) > 8;
  EXPECT_GT(differ, 100);
}

// Luma-weighted mean x of the frame's upper half of the flame.
double centroid_x(const test::Frame& f) {
  double sum = 0, wsum = 0;
  const int y_top = static_cast<int>(project({0, kSize.y, 0}).y);
  const int y_mid = static_cast<int>(project({0, kSize.y * 0.5f, 0}).y);
  for (int y = y_top; y < y_mid; ++y)
    for (int x = 0; x < kW; ++x) {
      sum += f.luma(x, y) * x;
      wsum += f.luma(x, y);
    }
  return wsum > 0 ? sum / wsum : 0;
}

TEST(PerlinFire, WindBendsTheFlameDownwind) {
  const std::string calm = scene(""),
                    windy = scene("", "flow3d", "[wind]\nspeed = 3.0\ndirection = [1, 0, 0]\n");
  // Wind blowing to +x: the upper flame moves right (a pixel is about 1 cm here).
  const double shift = centroid_x(render(windy, 90)) - centroid_x(render(calm, 90));
  EXPECT_GT(shift, 3.0);
}

TEST(PerlinFire, ObstacleHidesTheBaseOfTheFire) {
  const Vec2 base = project({0.0f, 0.1f * kSize.y, 0.5f * kSize.z});
  EXPECT_GT(mean_luma(render(scene(""), 4), base, 1), 40.0);
  EXPECT_EQ(mean_luma(render(scene("obstacle_height = 0.3"), 4), base, 1), 0.0);
}

// How far the fire's lowest lit pixel (luma above 40) rises and falls across
// the middle half of its width: the standard deviation of that row, in pixels.
double foot_spread(const test::Frame& f) {
  const int x0 = static_cast<int>(project({-0.25f * kSize.x, 0, 0}).x);
  const int x1 = static_cast<int>(project({0.25f * kSize.x, 0, 0}).x);
  std::vector<double> feet;
  for (int x = x0; x <= x1; ++x)
    for (int y = kH - 1; y >= 0; --y)
      if (f.luma(x, y) > 40) {
        feet.push_back(y);
        break;
      }
  if (feet.size() < static_cast<size_t>(x1 - x0) * 3 / 4) return -1;  // not a fire across it
  double mean = 0, var = 0;
  for (double y : feet) mean += y / feet.size();
  for (double y : feet) var += (y - mean) * (y - mean) / feet.size();
  return std::sqrt(var);
}

TEST(PerlinFire, ObstacleReliefLiftsTheFeetUnevenly) {
  // A flat obstacle cuts every flame at one height: their feet stand on a
  // straight line. With relief its top rises and falls across the fire (a
  // log pile's tops), so the feet do too, and still half a second later.
  const std::string flat =
      "profile_height = 0.9\nprofile_width = 0.97\nintensity = 18\nglow = 0\ntongue_gap = 0\n"
      "obstacle_height = 0.15\n";
  const test::Frame straight = render(scene(flat), 30, 5),
                    uneven = render(scene(flat + "obstacle_relief = 0.25"), 30, 5),
                    later = render(scene(flat + "obstacle_relief = 0.25"), 60, 5);
  const double s0 = foot_spread(straight), s1 = foot_spread(uneven), s2 = foot_spread(later);
  ASSERT_GE(s0, 0.0);
  ASSERT_GE(s1, 0.0);
  EXPECT_GT(s1, 3.0 * s0) << "flat " << s0;
  EXPECT_GT(s2, 3.0 * s0) << "flat " << s0;
}

TEST(PerlinFire, SwellMakesSomeFlamesTallerThanOthers) {
  // Without swell every part of a wide fire reaches about as high (a picket
  // fence of tips); with it the flames are taller in some places and lower in
  // others. The same fire (seed, time, turbulence) with and without: the lit
  // height of each column across most of its width, smoothed over a tongue's
  // width, five frames a second apart. A calm fire (little turbulence), whose
  // height the swell, not the noise, sets.
  const std::string calm =
      "profile_height = 0.5\nprofile_width = 0.97\nprofile_taper = 0.1\nintensity = 18\n"
      "glow = 0\ntongue_gap = 0\ndisplacement = 0.8\n";
  const int x0 = static_cast<int>(project({-0.3f * kSize.x, 0, 0}).x);
  const int x1 = static_cast<int>(project({0.3f * kSize.x, 0, 0}).x);
  const auto heights = [&](const test::Frame& f) {
    std::vector<double> lit;
    for (int x = x0; x <= x1; ++x) {
      double n = 0;
      for (int dx = -3; dx <= 3; ++dx)
        for (int y = 0; y < kH; ++y) n += f.luma(x + dx, y) > 40;
      lit.push_back(n / 7);
    }
    return lit;
  };
  const auto over_time = [&](const std::string& extra) {
    test::RenderHarness h(scene(calm + extra), kW, kH, 5);
    std::vector<std::vector<double>> out;
    for (int k = 0; k < 5; ++k) {
      h.run(60);
      out.push_back(heights(h.read()));
    }
    return out;
  };
  const auto even = over_time(""), swelling = over_time("swell = 0.7\n");
  int taller = 0, lower = 0, columns = 0;
  for (size_t k = 0; k < even.size(); ++k) {
    double area_even = 0, area_swelling = 0;
    for (size_t i = 0; i < even[k].size(); ++i) {
      ASSERT_GT(even[k][i], 5) << "no fire at column " << i;
      taller += swelling[k][i] > 1.15 * even[k][i];
      lower += swelling[k][i] < 0.87 * even[k][i];
      ++columns;
      area_even += even[k][i];
      area_swelling += swelling[k][i];
    }
    // Height moves from one place to another: the fire's lit area stays
    // (a swell that only added height made a real fire's area swing twice
    // as far as any real fire's).
    EXPECT_NEAR(area_swelling / area_even, 1.0, 0.1) << "frame " << k;
  }
  EXPECT_GT(taller, columns / 10);
  EXPECT_GT(lower, columns / 20);
}

// Luma summed over the rows between two heights of the volume (fractions of
// its height, through its centre), across the frame.
double band_luma(const test::Frame& f, float from, float to) {
  double sum = 0;
  const int y0 = static_cast<int>(project({0, kSize.y * to, 0}).y);
  const int y1 = static_cast<int>(project({0, kSize.y * from, 0}).y);
  for (int y = std::max(y0, 0); y < std::min(y1, kH); ++y)
    for (int x = 0; x < kW; ++x) sum += f.luma(x, y);
  return sum;
}

// Luma of the bed's rows (the lower half of the volume) summed down each
// column: where the tongues stand across the fire.
std::vector<double> tongue_columns(const test::Frame& f) {
  const int y0 = static_cast<int>(project({0, kSize.y * 0.5f, 0}).y);
  const int y1 = static_cast<int>(project({0, kSize.y * 0.05f, 0}).y);
  std::vector<double> columns(kW, 0.0);
  for (int y = std::max(y0, 0); y < std::min(y1, kH); ++y)
    for (int x = 0; x < kW; ++x) columns[x] += f.luma(x, y);
  return columns;
}

TEST(PerlinFire, TonguesThatDoNotRiseStandWhereTheyBurn) {
  // A few broad tongues, fast, little turbulence. Where the tongues stand
  // across the bed over one second: with `tongue_rise = 0` and a slow
  // `tongue_evolve` they stay put; the field rising (1) or changing in place
  // as fast as it would rise (`tongue_evolve = 1`) moves them.
  const std::string fire =
      "tongues = 6\ntongue_gap = 1\ntongue_width = 0.5\ntongue_roots = 1\ntongue_base = 0.05\n"
      "displacement = 0.1\nspeed = 3\nglow = 0\n";
  const auto kept = [&](const std::string& extra) {
    test::RenderHarness h(scene(fire + extra), kW, kH, 3);
    h.run(10);
    const test::Frame f0 = h.read();
    h.run(60);  // one second later
    return test::correlation(tongue_columns(f0), tongue_columns(h.read()));
  };
  const double standing = kept("tongue_rise = 0\ntongue_evolve = 0.03\n");
  const double rising = kept("tongue_rise = 1\ntongue_evolve = 0.03\n");
  const double evolving = kept("tongue_rise = 0\ntongue_evolve = 1\n");
  EXPECT_GT(standing, 0.9);
  EXPECT_LT(rising, standing - 0.1);
  EXPECT_LT(evolving, standing - 0.3);
}

// Separate lit pieces (luma > 40, at least 3 pixels, 4-connected) above a
// height of the volume (a fraction of its height, through its centre).
int pieces_above(const test::Frame& f, float from) {
  return f.regions_above(40, 3, std::max(0, static_cast<int>(project({0, kSize.y * from, 0}).y)));
}

// A few broad tongues that stand where their fuel burns (the tests of the
// fine field, the sway and the comb add how wide, how fast they change, how
// much turbulence).
const std::string kStandingTongues =
    "tongues = 5\ntongue_gap = 1\ntongue_roots = 1\ntongue_base = 0.05\ntongue_rise = 0\n"
    "glow = 0\n";

TEST(PerlinFire, FineTonguesTearTheTipsOverBroadTonguesThatStand) {
  // Broad tongues that stand where their fuel burns, with and without a fine
  // tongue field rising over them: with it, the flames' upper part is torn
  // into more pieces (tips tearing off, as a real fire's), while where the
  // broad tongues stand across the bed stays put over a second.
  const std::string broad =
      kStandingTongues + "tongue_width = 0.5\ntongue_evolve = 0.03\ndisplacement = 0.6\n";
  struct Seen {
    double pieces, kept;
  };
  // Where the tongues stand: the columns smoothed over a fine tongue's width.
  const auto smoothed = [](const std::vector<double>& c) {
    std::vector<double> out(c.size(), 0.0);
    for (size_t i = 0; i < c.size(); ++i)
      for (size_t j = i >= 3 ? i - 3 : 0; j < std::min(c.size(), i + 4); ++j) out[i] += c[j];
    return out;
  };
  const auto seen = [&](const std::string& extra) {
    test::RenderHarness h(scene(broad + extra), kW, kH, 3);
    h.run(10);
    const std::vector<double> first = smoothed(tongue_columns(h.read()));
    double pieces = 0;
    for (int k = 0; k < 6; ++k) {
      h.run(10);
      pieces += pieces_above(h.read(), 0.04f) / 6.0;
    }
    return Seen{pieces, test::correlation(first, smoothed(tongue_columns(h.read())))};
  };
  const Seen plain = seen(""), fine = seen("fine_gap = 1\nfine_tongues = 8\nfine_width = 0.25\n");
  ASSERT_GT(plain.kept, 0.9) << "the broad tongues do not stand";
  EXPECT_GT(fine.kept, 0.8);
  EXPECT_GT(fine.pieces, 1.3 * plain.pieces) << "without " << plain.pieces;
}

TEST(PerlinFire, TongueSwayMovesTheTonguesSidewaysNotAway) {
  // Broad tongues in a field that does not change in place: with a sway they
  // wander sideways over a few seconds (where they stand across the bed is
  // the first profile shifted), without it they stay; either way the fire
  // keeps about its light.
  const std::string broad =
      kStandingTongues +
      "tongue_width = 0.5\ntongue_evolve = 0\ndisplacement = 0.1\nbreathing = 0\n";
  struct Seen {
    int widest_shift;
    double light_low, light_high;
  };
  const auto seen = [&](const std::string& extra) {
    test::RenderHarness h(scene(broad + extra), kW, kH, 3);
    h.run(10);
    const std::vector<double> a = tongue_columns(h.read());
    double sa = 0;
    for (double v : a) sa += v;
    Seen out{0, 1e9, 0};
    for (int k = 0; k < 10; ++k) {
      h.run(30);  // every half second for five seconds
      const std::vector<double> b = tongue_columns(h.read());
      // The shift (pixels) that best lines this profile up with the first.
      int best = 0;
      double best_r = -2;
      for (int d = -20; d <= 20; ++d) {
        std::vector<double> x, y;
        for (int i = 0; i < kW; ++i)
          if (i + d >= 0 && i + d < kW) x.push_back(a[i]), y.push_back(b[i + d]);
        const double r = test::correlation(x, y);
        if (r > best_r) best_r = r, best = d;
      }
      double sb = 0;
      for (double v : b) sb += v;
      out.widest_shift = std::max(out.widest_shift, std::abs(best));
      out.light_low = std::min(out.light_low, sb / sa);
      out.light_high = std::max(out.light_high, sb / sa);
    }
    return out;
  };
  const Seen still = seen(""), swaying = seen("tongue_sway = 1\n");
  EXPECT_EQ(still.widest_shift, 0);
  EXPECT_GE(swaying.widest_shift, 4);
  EXPECT_GT(swaying.light_low, 0.85);
  EXPECT_LT(swaying.light_high, 1.15);
}

TEST(PerlinFire, TongueCombKeepsTheFiresLightSteady) {
  // A few broad tongues whose field changes in place: where its creases cut
  // the gaps, how much of the fire they take comes and goes with the field (a
  // few cells across the fire), and the fire's light swings; a comb of evenly
  // spaced gaps that wander along the field takes about the same share all the
  // time. The lit area sampled every quarter second for four seconds.
  const std::string broad =
      kStandingTongues +
      "tongue_width = 0.55\ntongue_evolve = 0.3\ndisplacement = 0.3\nbreathing = 0\n";
  const auto swing = [&](const std::string& extra) {
    test::RenderHarness h(scene(broad + extra), kW, kH, 3);
    std::vector<double> lit;
    for (int k = 0; k < 16; ++k) {
      h.run(15);
      lit.push_back(h.read().lit_above(40).count);
    }
    double mean = 0, var = 0;
    for (double v : lit) mean += v / lit.size();
    for (double v : lit) var += (v - mean) * (v - mean) / lit.size();
    EXPECT_GT(mean, 100) << "no fire";
    return std::sqrt(var) / mean;
  };
  const double creases = swing(""), comb = swing("tongue_comb = 0.4\n");
  EXPECT_LT(comb, 0.5 * creases) << "creases " << creases;
}

TEST(PerlinFire, CoolingDimsTheRisenFlamesNotTheBed) {
  // The same fire (one seed, one frame) with and without cooling: what rose
  // high (tips, pieces that broke off) is dim, while the bed, below where
  // cooling starts, keeps its light. A tall fire, as the fireplace's, without
  // the dim envelope (which cooling leaves alone).
  const std::string tall = "profile_height = 0.9\nintensity = 18\nglow = 0\n";
  const test::Frame hot = render(scene(tall), 30, 5),
                    cooled = render(scene(tall + "cooling = 1"), 30, 5);
  const double hot_bed = band_luma(hot, 0.0f, 0.12f), hot_top = band_luma(hot, 0.6f, 1.0f);
  ASSERT_GT(hot_bed, 0.0);
  ASSERT_GT(hot_top, 0.02 * hot_bed) << "nothing up high to cool";
  EXPECT_NEAR(band_luma(cooled, 0.0f, 0.12f) / hot_bed, 1.0, 0.02);
  EXPECT_LT(band_luma(cooled, 0.6f, 1.0f), 0.5 * hot_top);
}

TEST(PerlinFire, HaloLightsTheDarkAroundTheFlamesOnly) {
  // The same fire with and without the halo (at a reduced scale, where it is
  // drawn): pixels that were dark beside the flames take a dim warm light;
  // the flames themselves keep their colour; nothing is drawn outside the box.
  const std::string base = "glow = 0\nrender_scale = 0.5\n";
  const test::Frame plain = render(scene(base), 30, 5),
                    halo = render(scene(base + "halo = 1"), 30, 5);
  int r[4];
  box_rect(2, r);
  int newly_lit = 0, flames = 0, flames_changed = 0, outside = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const test::Rgba a = plain.at(x, y), b = halo.at(x, y);
      const bool inside = x >= r[0] && x <= r[2] && y >= r[1] && y <= r[3];
      if (!inside) {
        outside += b.r + b.g + b.b > 0;
        continue;
      }
      if (plain.luma(x, y) < 2 && halo.luma(x, y) >= 6) {
        ++newly_lit;
        EXPECT_GT(b.r, b.b) << "a halo pixel is not warm at " << x << "," << y;
      }
      if (plain.luma(x, y) > 150) {
        ++flames;
        flames_changed += std::abs(a.r - b.r) + std::abs(a.g - b.g) + std::abs(a.b - b.b) > 3;
      }
    }
  EXPECT_EQ(outside, 0);
  EXPECT_GT(newly_lit, 40);
  ASSERT_GT(flames, 20);
  EXPECT_LT(flames_changed, flames / 10);
}

TEST(PerlinFire, HaloRadiusSpreadsItsLightFurther) {
  // A wider halo lights more of the dark around the flames (a real fire's
  // light spreads far), at the same seed and time.
  const std::string base = "glow = 0\nrender_scale = 0.5\nhalo = 1\n";
  const test::Frame plain = render(scene("glow = 0\nrender_scale = 0.5\n"), 30, 5),
                    near = render(scene(base), 30, 5),
                    far = render(scene(base + "halo_radius = 0.15"), 30, 5);
  int lit_near = 0, lit_far = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x)
      if (plain.luma(x, y) < 2) {
        lit_near += near.luma(x, y) >= 6;
        lit_far += far.luma(x, y) >= 6;
      }
  ASSERT_GT(lit_near, 40);
  EXPECT_GT(lit_far, lit_near * 5 / 4) << "near " << lit_near;
}

// Mean |difference| of two frames' luma over the picture (gray levels).
double mean_change(const test::Frame& a, const test::Frame& b) {
  double sum = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) sum += std::abs(a.luma(x, y) - b.luma(x, y));
  return sum / (kW * kH);
}

TEST(PerlinFire, ShutterBlursTheMotionNotTheStillFlame) {
  // A camera's exposure time: a still fire (nothing rises, spins or
  // breathes) looks the same with and without the shutter, within the trail's
  // rounding; a moving one changes less from one frame to the next, as video
  // of a real fire does (its pieces smear over the exposure).
  const std::string base = "glow = 0\nrender_scale = 0.5\n";
  const std::string still = base + "speed = 0\nflow_speed = 0\nbreathing = 0\n";
  const test::Frame sharp = render(scene(still), 30, 5),
                    exposed = render(scene(still + "shutter = 0.05"), 30, 5);
  double lit = 0, worst = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      lit += sharp.luma(x, y) > 30;
      worst = std::max(worst, std::abs(sharp.luma(x, y) - exposed.luma(x, y)));
    }
  ASSERT_GT(lit, 200) << "no still flame to compare";
  EXPECT_LE(worst, 5.0);  // 8-bit rounding, steepened by the ramp; the fade alone, unlifted: 6.1
  EXPECT_LT(mean_change(sharp, exposed), 0.5);

  const auto frame_to_frame = [&](const std::string& extra) {
    test::RenderHarness h(scene(base + extra), kW, kH, 5);
    h.run(30);
    const test::Frame a = h.read();
    h.run(1);
    return mean_change(a, h.read());
  };
  const double instant = frame_to_frame(""), shutter = frame_to_frame("shutter = 0.05");
  ASSERT_GT(instant, 0.5) << "the fire does not move";
  EXPECT_LT(shutter, 0.75 * instant) << "instant " << instant;
}

TEST(PerlinFire, OccludeLetsTheLogsInFrontHideTheFire) {
  // Two logs across the fire's base: one in front of its middle plane, one
  // behind it. Occluding, the fire is one sheet through its middle: the front
  // log hides it (its pixels as without a fire), the back one does not (the
  // fire's light over it, as without occluding). Without, the fire is drawn
  // over both.
  const std::string logs = R"(
[[element]]
kind = "hearth"
position = [0.0, 0.0, 0.0]
width = 0.6
depth = 0.5
embers = 0
[[element.log]]
from = [-0.2, 0.05, 0.09]
to = [0.2, 0.05, 0.09]
radius = 0.045
[[element.log]]
from = [-0.2, 0.12, -0.1]
to = [0.2, 0.12, -0.1]
radius = 0.045
)";
  const std::string fire = "glow = 0\nrender_scale = 0.5\n";
  const test::Frame occluded = render(scene(fire + "occlude = true\n" + logs), 20, 5),
                    drawn_over = render(scene(fire + logs), 20, 5),
                    no_fire = render(scene(fire + "intensity = 0\n" + logs), 20, 5);
  const Vec2 front = project({0.0f, 0.05f, 0.09f + 0.045f}),
             back = project({0.0f, 0.12f + 0.03f, -0.1f});
  const double dark_front = mean_luma(no_fire, front, 1), dark_back = mean_luma(no_fire, back, 1);
  EXPECT_NEAR(mean_luma(occluded, front, 1), dark_front, 2.0);
  EXPECT_GT(mean_luma(drawn_over, front, 1), dark_front + 40);
  EXPECT_GT(mean_luma(occluded, back, 1), dark_back + 40);
  EXPECT_NEAR(mean_luma(occluded, back, 1), mean_luma(drawn_over, back, 1), 2.0);
}

TEST(PerlinFire, AutoQualityUnderAnImpossibleBudgetSettlesAtTheFloor) {
  // 10000 fps: every frame is over budget, so the governor must walk the
  // whole ladder down (scale, steps, octaves) and stay at its last rung,
  // which then draws exactly what that quality set by hand draws. Flame
  // sheets keep three slabs (9 steps): fewer leave the fire sparse.
  const std::string floor =
      scene("", "flow3d", "", "render_scale = 0.25\nsteps = 9\noctaves = 1\n");
  const std::string autoq = scene("quality = \"auto\"\ntarget_fps = 10000");
  for (int frames : {400, 430}) {
    SCOPED_TRACE(frames);
    EXPECT_EQ(render(autoq, frames, 0, true).rgba, render(floor, frames).rgba);
  }
  // With the budget met, the same scene keeps its full quality.
  const std::string top = scene("quality = \"auto\"\ntarget_fps = 1");
  EXPECT_NE(render(top, 400, 0, true).rgba, render(floor, 400).rgba);
  // A recording (lockstep, frame times not handed on) has no frame rate to
  // hold: under the impossible budget it still draws the scene's own top
  // quality, the same frames on a fast machine and a slow one.
  EXPECT_EQ(render(autoq, 400).rgba, render(scene(""), 400).rgba);
}

TEST(PerlinFire, BadSettingsNameTheKey) {
  try {
    load_scene_text(scene("", "simplex5d"), "fire.toml");
    FAIL() << "accepted noise = simplex5d";
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.key(), "element[0].noise");
    EXPECT_NE(std::string(e.what()).find("flow3d"), std::string::npos);
  }
  try {
    load_scene_text(scene("render_scale = 2.0"), "fire.toml");
    FAIL() << "accepted render_scale = 2";
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.key(), "element[0].render_scale");
  }
  try {  // the reduced-size fire is what is drawn as one sheet
    load_scene_text(scene("occlude = true\nrender_scale = 1"), "fire.toml");
    FAIL() << "accepted occlude at full scale";
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.key(), "element[0].occlude");
  }
  try {  // a shutter keeps its trail in the reduced-size target
    load_scene_text(scene("shutter = 0.03\nrender_scale = 1"), "fire.toml");
    FAIL() << "accepted a shutter at full scale";
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.key(), "element[0].shutter");
    EXPECT_NE(std::string(e.what()).find("render_scale"), std::string::npos);
  }
  try {
    load_scene_text(scene("cooling = 1.5"), "fire.toml");
    FAIL() << "accepted cooling = 1.5";
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.key(), "element[0].cooling");
  }
  try {
    load_scene_text(scene("profile = \"no-such-profile.png\""), "/tmp/fire.toml");
    FAIL() << "accepted a missing profile";
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.key(), "element[0].profile");
  }
}

TEST(PerlinFire, EveryBuiltInFireSceneLoads) {
  for (const char* name : {"perlin-fireplace", "bench-perlinfire-1", "bench-perlinfire-3"}) {
    SCOPED_TRACE(name);
    const SceneDesc d = load_builtin_scene(name);
    EXPECT_GE(d.elements.size(), 1u);
  }
}

// The fireplace is one fire that fills the picture (issue 35: at least 12% of
// the pixels above 0.25 gray and 45% of the frame's height, at 1280x720 and
// 1920x1080; it lit 10.7% before its body was widened), not separate fires
// side by side: through the fire's middle (30-60% of its height down from its
// top) no dark gap wider than 6% of the frame splits it (three separate
// volumes left gaps of 9-10%; gaps between tongues are narrower). At the
// scene's own top quality: its automatic quality would make what is measured
// depend on how fast this machine renders it. Without its firebox: the lit
// bricks are not fire. Also at the lowest quality its automatic quality goes
// down to on a slow board (render scale 0.25, octaves 1, steps 9: three
// slabs; at two it lit 8.9%).
class FireplaceFill : public ::testing::TestWithParam<std::tuple<int, int, bool>> {};

TEST_P(FireplaceFill, FillsThePictureAsOneFire) {
  const int kFw = std::get<0>(GetParam()), kFh = std::get<1>(GetParam());
  const auto lit = [](const test::Frame& f, int x, int y) { return f.luma(x, y) > 0.25 * 255; };
  std::string toml(scenes::find("perlin-fireplace.toml"));
  const auto at = toml.find("quality = \"auto\"");
  ASSERT_NE(at, std::string::npos);
  toml.replace(at, 16, "quality = \"fixed\"");
  if (std::get<2>(GetParam())) {
    for (const auto& [key, lowest] : {std::pair<std::string, std::string>{
                                          "render_scale = 0.5", "render_scale = 0.25\nsteps = 9"},
                                      {"octaves = 3", "octaves = 1"}}) {
      const auto k = toml.find(key);
      ASSERT_NE(k, std::string::npos) << key;
      toml.replace(k, key.size(), lowest);
    }
  }
  toml = test::without_table(toml, "[element.firebox]");
  ASSERT_FALSE(toml.empty());
  test::RenderHarness h(load_scene_text(toml, "perlin-fireplace.toml (fixed quality)"), kFw, kFh);
  double lit_share = 0;
  constexpr int kFrames = 4;
  for (int k = 0; k < kFrames; ++k) {
    h.run(10);
    const test::Frame f = h.read();
    const auto [count, top, bottom] = f.lit_above(0.25 * 255);
    lit_share += static_cast<double>(count) / (kFw * kFh);
    const int span = bottom - top + 1;
    EXPECT_GE(span, 0.45 * kFh) << "frame " << k;
    int first = -1, last = -1, gap = 0, widest_gap = 0;
    for (int x = 0; x < kFw; ++x) {
      int n = 0;
      for (int y = top + span * 3 / 10; y < top + span * 6 / 10; ++y) n += lit(f, x, y);
      if (n >= 4) {
        if (first < 0) first = x;
        last = x;
        widest_gap = std::max(widest_gap, gap);
        gap = 0;
      } else if (first >= 0) {
        ++gap;
      }
    }
    EXPECT_GE(last - first, 0.3 * kFw) << "frame " << k << ": the fire is narrower than the hearth";
    EXPECT_LE(widest_gap, 0.06 * kFw) << "frame " << k << ": a dark gap splits the fire";
  }
  EXPECT_GE(lit_share / kFrames, 0.12);
}

INSTANTIATE_TEST_SUITE_P(PerlinFire, FireplaceFill,
                         ::testing::Values(std::make_tuple(1280, 720, false),
                                           std::make_tuple(1920, 1080, false),
                                           std::make_tuple(1280, 720, true)),
                         [](const auto& info) {
                           return std::to_string(std::get<0>(info.param)) + "x" +
                                  std::to_string(std::get<1>(info.param)) +
                                  (std::get<2>(info.param) ? "_lowest_quality" : "");
                         });

}  // namespace
}  // namespace candela
