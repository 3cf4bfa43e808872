// The paper's fast warp (Beier-Neely at the vertices of an 8x8 mesh, drawn
// as textured triangles) against the exact per-pixel Beier-Neely warp.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "elements/candle/candle_rig.h"
#include "elements/candle/flame_still.h"
#include "elements/candle/flame_warp.h"
#include "scene/element.h"
#include "wind/wind_field.h"

namespace candela {
namespace {

constexpr double kStillPx = 256;  // the built-in still's height
constexpr double kAspect = 0.5;

// Where the built-in still is not transparent.
bool visible(WarpPoint p) {
  static const Image still = make_flame_still(static_cast<int>(kStillPx));
  const int x = static_cast<int>((p.x / kAspect + 0.5) * still.width);
  const int y = static_cast<int>((1 - p.y) * still.height);
  if (x < 0 || y < 0 || x >= still.width || y >= still.height) return false;
  return still.at(x, y, 3) > 8;
}

TEST(BeierNeely, OneLineMovedRotatedScaledIsTheAnalyticSimilarity) {
  // One line, translated by t, rotated by r about P, scaled by k along it:
  // points on the line scale by k; distance across it is kept.
  const WarpLine from{{0.0, 0.2}, {0.0, 0.8}};
  const double r = 0.4, k = 1.3, tx = 0.05, ty = -0.02;
  const double c = std::cos(r), s = std::sin(r);
  auto similarity = [&](WarpPoint x) {
    // Distance along the line from P (scaled by k) and across it (kept),
    // then the line turned by r about P and moved by t: its direction
    // (0, 1) becomes (-sin r, cos r), its normal (1, 0) becomes (cos r, sin r).
    const double along = (x.y - 0.2) * k, across = x.x;
    return WarpPoint{tx - along * s + across * c, ty + 0.2 + along * c + across * s};
  };
  // The destination line itself.
  const WarpPoint p2 = similarity({0.0, 0.2}), q2 = similarity({0.0, 0.8});
  const WarpLine to{p2, q2};
  for (const WarpPoint x : {WarpPoint{0.1, 0.5}, WarpPoint{-0.2, 0.9}, WarpPoint{0.05, 0.1}}) {
    const WarpPoint got = beier_neely(x, {&from, 1}, {&to, 1}, {});
    const WarpPoint want = similarity(x);
    EXPECT_NEAR(got.x, want.x, 1e-12);
    EXPECT_NEAR(got.y, want.y, 1e-12);
  }
  // The mesh reproduces it exactly (an affine map is linear on triangles).
  const WarpError e = mesh_warp_error(8, kAspect, {&from, 1}, {&to, 1}, {}, kStillPx);
  std::printf("[ warp ] one line: max %.2e px\n", e.max_px);
  EXPECT_LT(e.max_px, 1e-6);
}

// The mesh error for the paper's line sets, from a seeded run of a rig in
// calm and in breezes strong enough to make the flame stick to the wick.
TEST(BeierNeely, MeshErrorOnThePapersLineSetsIsSmall) {
  const auto source = to_warp_lines(source_lines(StillLayout{}));
  CandleParams p;
  p.extinguish_speed = Fixed::from_int(50);
  CandleRig rig(p, StillLayout{}, {}, 5);
  WindSpec spec;
  spec.breeze_interval = Fixed::from_int(3);
  spec.breeze_speed = Fixed::from_int(3);
  WindField wind(spec);
  StepContext step;
  step.dt = Fixed::from_ratio(1, 60);
  step.wind = &wind;
  double worst_calm = 0, worst_breeze = 0, worst_stuck = 0, sum = 0;
  int n = 0;
  for (int i = 0; i < 60 * 40; ++i) {
    wind.update(step);
    rig.update(step);
    if (i % 15) continue;
    auto dest = to_warp_lines(rig.lines());
    auto src = source;
    src.resize(dest.size());
    // The element's own mesh (FlameLook's default), as the GPU draws it.
    const WarpError e =
        mesh_warp_error(FlameLook{}.mesh, kAspect, src, dest, {}, kStillPx, 4, visible);
    const CandleState& s = rig.state();
    double& worst =
        s.stuck ? worst_stuck : (s.strength.to_double() > 0.2 ? worst_breeze : worst_calm);
    worst = std::max(worst, e.max_px);
    sum += e.mean_px;
    ++n;
  }
  std::printf(
      "[ warp ] default mesh vs exact, still %g px: max calm %.2f, breeze %.2f, stuck %.2f px; "
      "mean %.3f px\n",
      kStillPx, worst_calm, worst_breeze, worst_stuck, sum / n);
  EXPECT_GT(worst_stuck, 0.0) << "the run never made the flame stick";
  // Calm and breeze: within a pixel or two. Sticking adds V3, whose pull
  // toward the wick competes with V0's near the base; there the forward
  // (mesh) and backward (exact) warps part most.
  EXPECT_LT(worst_calm, 1.5);
  EXPECT_LT(worst_breeze, 3.0);
  EXPECT_LT(worst_stuck, 30.0);
  EXPECT_LT(sum / n, 2.0);
}

TEST(BeierNeely, FinerMeshesAreCloser) {
  CandleParams p;
  CandleRig rig(p, StillLayout{}, {}, 9);
  // Leaning in a steady wind from the left, not yet sticking.
  for (int i = 0; i < 240; ++i) rig.update({Fixed::from_ratio(1, 2), {}}, Fixed::from_ratio(1, 60));
  ASSERT_FALSE(rig.state().stuck);
  const auto dest = to_warp_lines(rig.lines());
  auto src = to_warp_lines(source_lines(StillLayout{}));
  src.resize(dest.size());
  const double e4 = mesh_warp_error(4, kAspect, src, dest, {}, kStillPx, 6, visible).max_px;
  const double e8 = mesh_warp_error(8, kAspect, src, dest, {}, kStillPx, 6, visible).max_px;
  const double e16 = mesh_warp_error(16, kAspect, src, dest, {}, kStillPx, 6, visible).max_px;
  std::printf("[ warp ] leaning flame: 4x4 %.2f, 8x8 %.2f, 16x16 %.2f px\n", e4, e8, e16);
  EXPECT_LT(e8, e4);
  EXPECT_LT(e16, e8);
}

}  // namespace
}  // namespace candela
