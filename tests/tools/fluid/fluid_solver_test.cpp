// The 2-D fire solver: incompressibility, buoyancy, cooling, stability and
// determinism, each checked against what the equations predict.
#include "fluid_solver.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "colour_map.h"
#include "fuel_bed.h"
#include "lattice_noise.h"
#include "pressure_solver.h"

namespace candela::fluid {
namespace {

// Still air, no forces: the baseline the tests switch terms on from.
FluidParams quiet_params(int w, int h) {
  FluidParams p;
  p.width = w;
  p.height = h;
  p.vorticity = 0.0;
  p.cooling = 0.0;
  p.sources.clear();
  return p;
}

void put_blob(Grid2& t, double cx, double cy, double r, double temp) {
  for (int j = 0; j < t.height; ++j)
    for (int i = 0; i < t.width; ++i)
      if (std::hypot(i + 0.5 - cx, j + 0.5 - cy) < r) t.at(i, j) = temp;
}

// Centre of mass of |T - T_amb|, in cells.
double centroid_y(const Grid2& t, double amb) {
  double m = 0.0, my = 0.0;
  for (int j = 0; j < t.height; ++j)
    for (int i = 0; i < t.width; ++i) {
      const double w = std::fabs(t.at(i, j) - amb);
      m += w;
      my += w * (j + 0.5);
    }
  return my / m;
}

// Stated bound: after projection, max over cells of |div u| * cell is at most
// pressure_tolerance (1e-5) times the largest face speed.
TEST(FluidSolver, ProjectionLeavesDivergenceBelowStatedBound) {
  for (bool side_walls : {false, true}) {
    FluidParams p = quiet_params(67, 45);  // odd sizes exercise the uneven multigrid levels
    p.boundary.open_left = p.boundary.open_right = !side_walls;
    FluidSolver s(p);
    Pcg32 rng(7);
    for (double& x : s.u().data) x = 40.0 * (rng.unit_double() - 0.5);
    for (double& x : s.v().data) x = 40.0 * (rng.unit_double() - 0.5);
    const double before = std::max(s.u().max_abs(), s.v().max_abs());
    Grid2 div;
    s.divergence(div);
    const double div_before = div.max_abs();
    const PressureStats st = s.project();
    s.divergence(div);
    EXPECT_TRUE(st.converged);
    EXPECT_LT(st.iterations, 30) << "multigrid-preconditioned CG should need few iterations";
    EXPECT_LE(div.max_abs(), 1e-5 * before) << "side walls " << side_walls;
    EXPECT_GT(div_before, 1e3 * div.max_abs());
    // Walls stay shut.
    if (side_walls) {
      for (int j = 0; j < p.height; ++j) EXPECT_EQ(s.u().at(0, j), 0.0);
    }
    for (int i = 0; i < p.width; ++i) EXPECT_EQ(s.v().at(i, 0), 0.0);
  }
}

TEST(FluidSolver, DivergenceStaysBoundedInARunningFire) {
  FluidParams p;  // defaults: one source, buoyancy, vorticity, cooling
  p.width = 48;
  p.height = 64;
  p.sources = {HeatSource{}};
  FluidSolver s(p);
  Grid2 div;
  for (int k = 0; k < 60; ++k) {
    const StepStats st = s.step(1.0 / 60.0);
    ASSERT_TRUE(st.pressure.converged) << "step " << k;
    s.divergence(div);
    ASSERT_LE(div.max_abs(), 2e-5 * st.max_speed + 1e-12) << "step " << k;
  }
}

TEST(FluidSolver, HotBlobRisesColdBlobSinksOrStays) {
  const double amb = 300.0;
  FluidParams p = quiet_params(48, 64);
  FluidSolver hot(p), cold(p);
  put_blob(hot.temperature(), 24, 20, 6, amb + 600.0);
  put_blob(cold.temperature(), 24, 20, 6, amb - 100.0);
  const double y_hot0 = centroid_y(hot.temperature(), amb);
  const double y_cold0 = centroid_y(cold.temperature(), amb);
  for (int k = 0; k < 45; ++k) {
    hot.step(1.0 / 30.0);
    cold.step(1.0 / 30.0);
  }
  const double rise_hot = centroid_y(hot.temperature(), amb) - y_hot0;
  const double rise_cold = centroid_y(cold.temperature(), amb) - y_cold0;
  // Constant acceleration kappa_b dT = 30 cells/s^2 for 1.5 s would lift a
  // free parcel 34 cells; drag from the surrounding air keeps it below that.
  EXPECT_GT(rise_hot, 5.0);
  EXPECT_LT(rise_hot, 34.0);
  EXPECT_LE(rise_cold, 0.0);
}

// With no flow and no sources, each cell follows
// dT/dt = -C_r ((T - T_amb)/(T_max - T_amb))^4, T_max the hottest cell.
TEST(FluidSolver, CoolingFollowsTheRadiativeCoolingOde) {
  const double amb = 300.0, cr = 400.0;
  FluidParams p = quiet_params(16, 16);
  p.buoyancy = 0.0;
  p.cooling = cr;
  FluidSolver s(p);
  Grid2& t = s.temperature();
  t.fill(amb + 300.0);
  for (int i = 0; i < 8; ++i) t.at(i, 8) = amb + 1000.0;  // the hottest row
  const double dt = 1.0 / 60.0, total = 2.0;
  for (int k = 0; k < static_cast<int>(total / dt + 0.5); ++k) s.step(dt);
  // Reference: the hottest cell drops linearly (s = 1), the others by RK4 on
  // the coupled pair with a fine step.
  double hot = 1000.0, warm = 300.0;
  const double h = 1e-4;
  auto rate = [&](double x, double m) { return -cr * std::pow(x / m, 4.0); };
  for (int k = 0; k < static_cast<int>(total / h + 0.5); ++k) {
    const double k1h = rate(hot, hot), k1w = rate(warm, hot);
    const double h2 = hot + 0.5 * h * k1h, w2 = warm + 0.5 * h * k1w;
    const double k2h = rate(h2, h2), k2w = rate(w2, h2);
    const double h3 = hot + 0.5 * h * k2h, w3 = warm + 0.5 * h * k2w;
    const double k3h = rate(h3, h3), k3w = rate(w3, h3);
    const double h4 = hot + h * k3h, w4 = warm + h * k3w;
    const double k4h = rate(h4, h4), k4w = rate(w4, h4);
    hot += h / 6.0 * (k1h + 2 * k2h + 2 * k3h + k4h);
    warm += h / 6.0 * (k1w + 2 * k2w + 2 * k3w + k4w);
  }
  EXPECT_NEAR(hot, 200.0, 1e-6);  // 1000 - C_r * 2 s
  EXPECT_NEAR(t.at(3, 8) - amb, hot, 0.01 * 1000.0);
  EXPECT_NEAR(t.at(3, 3) - amb, warm, 0.01 * 300.0);
  EXPECT_LT(t.at(3, 3) - amb, 300.0 - 30.0) << "the warm cells must have cooled visibly";
}

TEST(FluidSolver, StableAtLargeTimeSteps) {
  FluidParams p;
  p.width = 48;
  p.height = 48;
  p.sources = {HeatSource{}};
  p.wind = {{0.0, 0.0}, {5.0, 60.0}};
  const double dt = 0.25;  // flow moves tens of cells per step: CFL >> 1
  FluidSolver s(p);
  double max_e = 0.0;
  for (int k = 0; k < 120; ++k) {
    s.step(dt);
    max_e = std::max(max_e, s.kinetic_energy());
    for (double x : s.u().data) ASSERT_TRUE(std::isfinite(x)) << "step " << k;
    for (double x : s.temperature().data) ASSERT_TRUE(std::isfinite(x)) << "step " << k;
  }
  // Bound: every face no faster than a parcel accelerated by the hottest
  // buoyancy across the whole height, v^2 = 2 kappa_b dT H, plus the wind.
  const double dT = HeatSource{}.temperature - p.t_ambient;
  const double vmax = std::sqrt(2.0 * p.buoyancy * dT * p.height) + 60.0;
  const double faces = (p.width + 1.0) * p.height + p.width * (p.height + 1.0);
  EXPECT_LT(max_e, 0.5 * vmax * vmax * faces);
  EXPECT_LT(std::max(s.u().max_abs(), s.v().max_abs()), 2.0 * vmax);
  // The temperature stays between ambient and the source temperature.
  for (double x : s.temperature().data) {
    EXPECT_GE(x, p.t_ambient - 1e-9);
    EXPECT_LE(x, HeatSource{}.temperature + 1e-9);
  }
}

TEST(FluidSolver, SameSeedSameFieldsOtherSeedOtherFields) {
  FluidParams p;
  p.width = 32;
  p.height = 48;
  p.sources = {HeatSource{}};
  auto run = [&](uint64_t seed) {
    p.seed = seed;
    FluidSolver s(p);
    for (int k = 0; k < 40; ++k) s.step(1.0 / 60.0);
    return s.temperature().data;
  };
  const auto a = run(3), b = run(3), c = run(4);
  EXPECT_EQ(a, b);
  double diff = 0.0;
  for (size_t k = 0; k < a.size(); ++k) diff = std::max(diff, std::fabs(a[k] - c[k]));
  EXPECT_GT(diff, 1.0) << "the seed must change the flame";
}

// A Gaussian ridge carried by a uniform wind: MacCormack must keep it far
// closer to the exactly translated profile than one semi-Lagrangian pass
// (whose bilinear resampling smears it every step), and add no new extrema.
TEST(FluidSolver, MacCormackKeepsATranslatedProfileFarBetterThanSemiLagrangian) {
  const double amb = 300.0, speed = 7.3, dt = 1.0 / 30.0, x0 = 24.0, sigma = 4.0;
  const int steps = 90;  // 21.9 cells
  auto profile = [&](double x) { return amb + 500.0 * std::exp(-0.5 * std::pow(x / sigma, 2.0)); };
  auto run = [&](Advection a, double& peak, double& lo, double& hi) {
    FluidParams p = quiet_params(96, 12);
    p.buoyancy = 0.0;
    p.advection = a;
    FluidSolver s(p);
    for (double& u : s.u().data) u = speed;
    for (int j = 0; j < 12; ++j)
      for (int i = 0; i < 96; ++i) s.temperature().at(i, j) = profile(i + 0.5 - x0);
    lo = 1e300;
    hi = -1e300;
    for (int k = 0; k < steps; ++k) {
      s.step(dt);
      for (double t : s.temperature().data) {
        lo = std::min(lo, t);
        hi = std::max(hi, t);
      }
    }
    double err = 0.0;
    peak = 0.0;
    for (int i = 0; i < 96; ++i) {
      const double t = s.temperature().at(i, 6);
      err += std::pow(t - profile(i + 0.5 - x0 - speed * dt * steps), 2.0);
      peak = std::max(peak, t - amb);
    }
    return std::sqrt(err / 96.0);
  };
  double peak_sl = 0, peak_mc = 0, lo = 0, hi = 0;
  const double err_sl = run(Advection::kSemiLagrangian, peak_sl, lo, hi);
  const double err_mc = run(Advection::kMacCormack, peak_mc, lo, hi);
  std::printf(
      "translated ridge, rms error: semi-Lagrangian %.2f K (peak %.0f K), MacCormack "
      "%.2f K (peak %.0f K) of 500 K\n",
      err_sl, peak_sl, err_mc, peak_mc);
  EXPECT_LT(err_mc, 0.35 * err_sl);
  EXPECT_GT(peak_mc, 0.9 * 500.0);
  EXPECT_LT(peak_sl, 0.8 * 500.0) << "the baseline must show the smearing MacCormack removes";
  EXPECT_GE(lo, amb - 1e-9) << "clamped: no undershoot";
  EXPECT_LE(hi, amb + 500.0 + 1e-9) << "clamped: no overshoot";
}

// Vorticity confinement puts back the swirl that advection smears away: the
// same random flow keeps measurably more |curl u| with it than without.
TEST(FluidSolver, VorticityConfinementAddsMeasuredVorticity) {
  auto run = [&](double eps, double& start) {
    FluidParams p = quiet_params(64, 64);
    p.buoyancy = 0.0;
    p.vorticity = eps;
    p.boundary.open_left = p.boundary.open_right = false;
    FluidSolver s(p);
    Pcg32 rng(11);
    for (double& x : s.u().data) x = 30.0 * (rng.unit_double() - 0.5);
    for (double& x : s.v().data) x = 30.0 * (rng.unit_double() - 0.5);
    s.project();
    start = s.mean_abs_vorticity();
    for (int k = 0; k < 30; ++k) s.step(1.0 / 30.0);
    return s.mean_abs_vorticity();
  };
  double w0 = 0.0;
  const double plain = run(0.0, w0), confined = run(3.0, w0);
  std::printf(
      "mean |curl u|: start %.2f/s, after 1 s without confinement %.2f/s, with eps=3 "
      "%.2f/s\n",
      w0, plain, confined);
  EXPECT_LT(plain, 0.7 * w0) << "advection alone must lose swirl (the baseline)";
  EXPECT_GT(confined, 1.5 * plain);
}

// Fuel above ignition burns as exp(-burn_rate t) and turns into heat_release
// kelvin per unit; below ignition it waits. Without flow and cooling, fuel *
// heat_release + T is conserved cell by cell.
TEST(FluidSolver, CombustionBurnsAtTheStatedRateAndConservesEnergy) {
  FluidParams p = quiet_params(16, 16);
  p.buoyancy = 0.0;
  p.advection = Advection::kMacCormack;
  p.burn_rate = 3.0;
  p.ignition = 600.0;
  p.heat_release = 250.0;
  FluidSolver s(p);
  for (int j = 0; j < 16; ++j)
    for (int i = 0; i < 16; ++i) {
      s.temperature().at(i, j) = i < 8 ? 900.0 : 400.0;
      s.fuel().at(i, j) = 1.0;
    }
  const double dt = 1.0 / 60.0;
  for (int k = 0; k < 30; ++k) s.step(dt);
  const double left = std::exp(-3.0 * 0.5);
  EXPECT_NEAR(s.fuel().at(3, 5), left, 1e-9);
  EXPECT_NEAR(s.temperature().at(3, 5), 900.0 + 250.0 * (1.0 - left), 1e-6);
  EXPECT_EQ(s.fuel().at(12, 5), 1.0) << "below ignition nothing burns";
  EXPECT_EQ(s.temperature().at(12, 5), 400.0);

  // No cell burns hotter than the flame temperature.
  p.flame_temperature = 1000.0;
  FluidSolver c(p);
  c.temperature().fill(900.0);
  c.fuel().fill(1.0);
  for (int k = 0; k < 30; ++k) c.step(dt);
  EXPECT_DOUBLE_EQ(c.temperature().max_abs(), 1000.0);
  EXPECT_NEAR(c.fuel().at(3, 5), left, 1e-9) << "the fuel still burns at the stated rate";
}

// A log with turbulent injection feeds fuel in patches along its length (the
// roots of separate tongues); without it the feed is even.
TEST(FluidSolver, TurbulentInjectionFeedsALogInPatches) {
  auto feed_cv = [&](double turbulence) {
    FluidParams p = quiet_params(200, 40);
    p.buoyancy = 0.0;
    p.jitter = 0.0;
    p.burn_rate = 0.0;
    HeatSource log;
    log.x = 0.5;
    log.y = 0.5;
    log.rx = 0.45;
    log.ry = 0.1;
    log.rate = 0.0;
    log.flicker = 0.0;
    log.fuel = 10.0;
    log.turbulence = turbulence;
    log.grain = 8.0;
    p.sources = {log};
    FluidSolver s(p);
    s.step(1.0 / 60.0);
    double m = 0.0, m2 = 0.0;
    const int n = 60;  // the middle of the log, where the ellipse is nearly flat
    for (int i = 70; i < 70 + n; ++i) {
      const double f = s.fuel().at(i, 20);
      m += f;
      m2 += f * f;
    }
    m /= n;
    return std::sqrt(std::max(0.0, m2 / n - m * m)) / m;
  };
  const double even = feed_cv(0.0), patchy = feed_cv(0.9);
  std::printf("fuel feed along a log, coefficient of variation: %.3f plain, %.3f turbulent\n", even,
              patchy);
  EXPECT_LT(even, 0.15);
  EXPECT_GT(patchy, 0.4);
}

// A camera on black-body radiance: visible luminance climbs steeply with T,
// so a temperature ramp renders with a far narrower edge than the normalised
// temperature gives, and the hottest gas clips to white.
TEST(Radiance, CrispEdgeAndClippedCore) {
  EXPECT_GT(black_body_luminance(1900.0) / black_body_luminance(900.0), 500.0);
  const double amb = 300.0, tref = 1900.0;
  Grid2 ramp(200, 1);
  for (int i = 0; i < 200; ++i) ramp.at(i, 0) = amb + (tref - amb) * (i + 0.5) / 200.0;
  Camera cam;
  cam.exposure = 4.0;
  const Image r = render_radiance(ramp, amb, tref, ColourMode::kGray, cam, 1);
  const Image g = render_temperature(ramp, amb, tref, ColourMode::kGray, 1);
  auto band = [](const Image& im) {  // pixels with gray in the measure's edge band 0.15..0.6
    int n = 0;
    for (int x = 0; x < im.width; ++x) {
      const double v = im.row(0)[x] / 255.0;
      n += v > 0.15 && v < 0.6;
    }
    return n;
  };
  std::printf(
      "edge band 0.15..0.6 over a 1600 K ramp of 200 cells: temperature %d px, "
      "radiance %d px\n",
      band(g), band(r));
  EXPECT_LT(band(r), band(g) / 2);
  EXPECT_GE(r.row(0)[199], 250) << "the hottest gas clips to white";
  int white = 0;
  for (int x = 0; x < 200; ++x) white += r.row(0)[x] >= 243;
  EXPECT_GT(white, 10);
  for (int x = 1; x < 200; ++x) ASSERT_GE(r.row(0)[x], r.row(0)[x - 1]) << "monotone in T";
  // Soot: hot gas without fuel is clear (invisible); with fuel it glows.
  Grid2 hot(2, 1, 1800.0), fuel(2, 1, 0.0);
  fuel.at(1, 0) = 50.0;
  cam.soot = 10.0;
  const Image s = render_radiance(hot, amb, tref, ColourMode::kGray, cam, 1, &fuel);
  EXPECT_EQ(s.row(0)[0], 0);
  EXPECT_GT(s.row(0)[1], 240);
  // Soft clip: continuous at the knee, below 1 always.
  EXPECT_NEAR(soft_clip(0.7 - 1e-9, 0.7), soft_clip(0.7 + 1e-9, 0.7), 1e-6);
  EXPECT_LT(soft_clip(3.0, 0.7), 1.0);
  EXPECT_GT(soft_clip(3.0, 0.7), 0.95);
}

// A slice placed 1:1 at the canvas's corner is render_radiance's picture
// (same light, same clip); mirrored and shifted it lands where it is told.
TEST(Radiance, SliceOnACanvasIsTheSameLight) {
  const double amb = 300.0, tref = 1900.0;
  Grid2 t(12, 10, amb), fuel(12, 10, 40.0);
  for (int j = 0; j < 10; ++j)
    for (int i = 0; i < 12; ++i) t.at(i, j) = amb + 130.0 * i + 20.0 * j;
  Camera cam;
  cam.exposure = 2.5;
  cam.knee = 0.8;
  cam.soot = 30.0;
  const Image ref = render_radiance(t, amb, tref, ColourMode::kGray, cam, 1, &fuel);
  std::vector<float> canvas;
  SlicePlacement at;
  add_radiance(t, &fuel, RadianceTable(amb, tref), cam, at, 12, 10, canvas);
  const Image got = finish_radiance(canvas, 12, 10, cam);
  ASSERT_EQ(got.pixels.size(), ref.pixels.size());
  for (size_t i = 0; i < ref.pixels.size(); ++i)
    ASSERT_NEAR(got.pixels[i], ref.pixels[i], 1) << "pixel " << i;
  // Mirrored, 5 px to the right, 2 rows up on a 20x12 canvas.
  std::vector<float> wide;
  at.left = 5.0;
  at.bottom = 2.0;
  at.mirror = true;
  add_radiance(t, &fuel, RadianceTable(amb, tref), cam, at, 20, 12, wide);
  const Image m = finish_radiance(wide, 20, 12, cam);
  for (int y = 0; y < 10; ++y)
    for (int x = 0; x < 12; ++x) ASSERT_NEAR(m.at(5 + 11 - x, y), ref.at(x, y), 1) << x << "," << y;
  for (int y = 0; y < 12; ++y) EXPECT_EQ(m.at(2, y), 0) << "outside the slice stays dark";
  EXPECT_EQ(m.at(10, 11), 0) << "below the raised slice stays dark";
  // Light adds: the same slice twice is twice the exposure.
  add_radiance(t, &fuel, RadianceTable(amb, tref), cam, SlicePlacement{}, 12, 10, canvas);
  Camera twice = cam;
  twice.exposure = 5.0;
  const Image two = render_radiance(t, amb, tref, ColourMode::kGray, twice, 1, &fuel);
  const Image sum = finish_radiance(canvas, 12, 10, cam);
  for (size_t i = 0; i < two.pixels.size(); ++i) ASSERT_NEAR(sum.pixels[i], two.pixels[i], 1);
}

// The camera's glow spreads bright light past a tongue's edge and fills a
// narrow gap between two tongues; the haze lights the dark around the fire
// but never above its own brightness, so it cannot join pieces on its own.
TEST(Radiance, GlowFillsNarrowGapsHazeStaysDim) {
  const int w = 64, h = 32;
  std::vector<float> canvas(static_cast<size_t>(w) * h, 0.0f);
  // Two bright tongues, 3 px apart.
  for (int y = 4; y < 28; ++y)
    for (int x = 20; x < 43; ++x)
      if (x < 30 || x >= 33) canvas[static_cast<size_t>(y) * w + x] = 3.0f;
  Camera plain;
  plain.knee = 0.6;
  const Image a = finish_radiance(canvas, w, h, plain);
  EXPECT_EQ(a.at(31, 16), 0) << "no glow: the gap stays black";
  EXPECT_GT(a.at(25, 16), 250) << "the tongues are clipped white";
  Camera glow = plain;
  glow.glow = 0.3;
  glow.glow_radius = 3.0;
  const Image g = finish_radiance(canvas, w, h, glow);
  EXPECT_GT(g.at(31, 16), 0.25 * 255) << "the glow fills the gap above the flame threshold";
  EXPECT_GT(g.at(17, 16), a.at(17, 16) + 20) << "and lights just past the outer edge";
  EXPECT_LT(g.at(5, 16), 0.1 * 255) << "but not far from it";
  Camera haze = plain;
  haze.haze = 0.04;
  haze.haze_radius = 8.0;
  const Image z = finish_radiance(canvas, w, h, haze);
  EXPECT_GT(z.at(17, 16), 0.1 * 255) << "the haze lights the dark beside the fire";
  const double ceiling = 255.0 * 0.22;  // sRGB of linear 0.04, rounded up
  for (int x = 0; x < 18; ++x) ASSERT_LE(z.at(x, 16), ceiling) << "x " << x;
  EXPECT_LE(z.at(31, 16), ceiling) << "the haze alone does not join the tongues";
}

// The slices' flicker is pink: unit spread about zero, even power per
// octave (a 1/f spectrum, slope about -1 between 0.75 and 12 Hz), different
// per seed. (A white or red flicker would miss the real fires' spectra.)
TEST(PinkFlicker, UnitSpreadAndOneOverFSpectrum) {
  const double fps = 96.0;
  const int n = 96 * 600;  // 10 minutes
  std::vector<double> x(n);
  double mean = 0.0, var = 0.0;
  for (int i = 0; i < n; ++i) mean += x[i] = pink_flicker(5, i / fps);
  mean /= n;
  for (double v : x) var += (v - mean) * (v - mean);
  const double sd = std::sqrt(var / n);
  EXPECT_NEAR(mean, 0.0, 0.1);
  EXPECT_NEAR(sd, 1.0, 0.15) << "sd " << sd;
  // Averaged periodograms of 4-s Hann windows; power in octave bands.
  const int seg = 4 * 96;
  std::vector<double> psd(seg / 2 + 1, 0.0);
  for (int s = 0; s + seg <= n; s += seg / 2)
    for (int k = 1; k <= seg / 2; ++k) {
      double re = 0.0, im = 0.0;
      for (int j = 0; j < seg; ++j) {
        const double w = 0.5 - 0.5 * std::cos(2.0 * M_PI * j / seg);
        const double a = 2.0 * M_PI * k * j / seg;
        re += w * x[s + j] * std::cos(a);
        im -= w * x[s + j] * std::sin(a);
      }
      psd[k] += re * re + im * im;
    }
  std::vector<double> lf, lp;
  for (double lo = 0.75; lo < 12.0; lo *= 2.0) {
    double p = 0.0;
    int cnt = 0;
    for (int k = 1; k <= seg / 2; ++k) {
      const double hz = k * fps / seg;
      if (hz >= lo && hz < 2.0 * lo) p += psd[k], ++cnt;
    }
    lf.push_back(std::log10(lo * std::sqrt(2.0)));
    lp.push_back(std::log10(p / cnt));
  }
  double mf = 0.0, mp = 0.0, sfp = 0.0, sff = 0.0;
  for (size_t i = 0; i < lf.size(); ++i) mf += lf[i] / lf.size(), mp += lp[i] / lp.size();
  for (size_t i = 0; i < lf.size(); ++i)
    sfp += (lf[i] - mf) * (lp[i] - mp), sff += (lf[i] - mf) * (lf[i] - mf);
  const double slope = sfp / sff;
  EXPECT_GT(slope, -1.5) << "not red";
  EXPECT_LT(slope, -0.5) << "not white";
  int same = 0;
  for (int i = 0; i < 1000; ++i) same += pink_flicker(5, i / fps) == pink_flicker(6, i / fps);
  EXPECT_LT(same, 10) << "each seed flickers on its own";
}

// The fuel bed: the front log hides the flames behind it and is lit by them;
// flames add over the logs behind; charred wood glows in cracks that pulse;
// coals glow only under the logs.
TEST(FuelBed, FrontLogHidesFlamesLogsBehindShowThrough) {
  const int w = 160, h = 120;
  const FuelBed bed = hearth_fuel_bed(w, h, 7);
  ASSERT_EQ(bed.logs.size(), 3u);
  const Log& front = bed.logs[2];
  ASSERT_TRUE(front.in_front);
  // Flames: a bright band over the whole lower half.
  std::vector<float> flames(static_cast<size_t>(w) * h, 0.0f);
  for (int y = h / 2; y < h; ++y)
    for (int x = 0; x < w; ++x) flames[static_cast<size_t>(y) * w + x] = 0.8f;
  std::vector<float> lit = flames, dark(static_cast<size_t>(w) * h, 0.0f);
  draw_fuel_bed(bed, 1.0, w, h, lit);
  draw_fuel_bed(bed, 1.0, w, h, dark);
  auto at = [&](const std::vector<float>& c, double x, double y) {
    return c[static_cast<size_t>(y) * w + static_cast<size_t>(x)];
  };
  const double fx = 0.5 * (front.x0 + front.x1), fy = 0.5 * (front.y0 + front.y1);
  // The front log's middle is wood, not flame: far below the flames' 0.8.
  EXPECT_LT(at(lit, fx, fy), 0.3f);
  // Its top faces the flames and is lit by them; unlit it is darker.
  const double top = fy - 0.7 * front.radius;
  EXPECT_GT(at(lit, fx, top), at(dark, fx, top) + 0.01f);
  EXPECT_GT(at(lit, fx, top), at(lit, fx, fy + 0.7 * front.radius));
  // A log behind: the flames' light adds over it.
  const Log& back = bed.logs[0];
  const double bx = 0.5 * (back.x0 + back.x1), by = 0.5 * (back.y0 + back.y1);
  ASSERT_GE(by, h / 2.0) << "the back log stands in the flames";
  EXPECT_GE(at(lit, bx, by), 0.8f);
  // Above the logs and coals nothing is drawn.
  EXPECT_EQ(at(dark, w / 2, 5), 0.0f);
  // Char glows in cracks, somewhere on the logs, and the glow changes in time.
  std::vector<float> later(static_cast<size_t>(w) * h, 0.0f);
  draw_fuel_bed(bed, 4.0, w, h, later);
  double peak = 0.0, change = 0.0;
  for (size_t i = 0; i < dark.size(); ++i) {
    peak = std::max(peak, static_cast<double>(dark[i]));
    change += std::fabs(dark[i] - later[i]);
  }
  EXPECT_GT(peak, 0.1) << "glowing cracks or coals";
  EXPECT_GT(change / dark.size(), 1e-4) << "the glow pulses";
}

// Without its back logs the bed keeps the front log and coals as they were,
// and the flames above the front log are the simulation's own light: no lit
// log top through them (the eigen fireplace showed one as a straight band).
TEST(FuelBed, WithoutBackLogsFlamesAboveTheFrontLogAreTheirOwnLight) {
  const int w = 160, h = 120;
  const FuelBed full = hearth_fuel_bed(w, h, 7), front_only = hearth_fuel_bed(w, h, 7, false);
  ASSERT_EQ(front_only.logs.size(), 1u);
  ASSERT_TRUE(front_only.logs[0].in_front);
  std::vector<float> flames(static_cast<size_t>(w) * h, 0.0f);
  for (int y = h / 2; y < h; ++y)
    for (int x = 0; x < w; ++x) flames[static_cast<size_t>(y) * w + x] = 0.6f;
  std::vector<float> with = flames, without = flames;
  draw_fuel_bed(full, 1.0, w, h, with);
  draw_fuel_bed(front_only, 1.0, w, h, without);
  auto at = [&](const std::vector<float>& c, double x, double y) {
    return c[static_cast<size_t>(y) * w + static_cast<size_t>(x)];
  };
  // Along the back logs' lit tops: wood under the flames with them, none without.
  for (int i = 0; i < 2; ++i) {
    const Log& back = full.logs[static_cast<size_t>(i)];
    const double bx = 0.5 * (back.x0 + back.x1), by = 0.5 * (back.y0 + back.y1) - 0.7 * back.radius;
    EXPECT_GT(at(with, bx, by), 0.6f + 0.005f) << "back log " << i;
    EXPECT_EQ(at(without, bx, by), 0.6f) << "back log " << i;
  }
  // The front log (along its axis) and the coals below it are the same either way.
  const Log& front = full.logs[2];
  for (double t = 0.05; t < 1.0; t += 0.1) {
    const double x = front.x0 + t * (front.x1 - front.x0), y = front.y0 + t * (front.y1 - front.y0);
    EXPECT_EQ(at(with, x, y), at(without, x, y)) << "front log at " << t;
  }
  for (int y = static_cast<int>(std::max(front.y0, front.y1) + front.radius) + 1; y < h; ++y)
    for (int x = 0; x < w; x += 7) ASSERT_EQ(at(with, x, y), at(without, x, y)) << x << "," << y;
}

TEST(FluidSolver, RejectsBadParametersByName) {
  FluidParams p;
  p.width = 4;
  EXPECT_THROW(
      {
        try {
          validate(p);
        } catch (const std::invalid_argument& e) {
          EXPECT_NE(std::string(e.what()).find("width"), std::string::npos);
          throw;
        }
      },
      std::invalid_argument);
  p = FluidParams{};
  p.sources = {HeatSource{}};
  p.sources[0].temperature = 100.0;
  EXPECT_THROW(validate(p), std::invalid_argument);
  p = FluidParams{};
  p.wind = {{1.0, 0.0}, {1.0, 3.0}};
  EXPECT_THROW(validate(p), std::invalid_argument);
  p = FluidParams{};
  p.sources = {HeatSource{}};
  p.sources[0].turbulence = 1.5;
  try {
    validate(p);
    ADD_FAILURE() << "turbulence 1.5 accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("source 1 turbulence"), std::string::npos) << e.what();
  }
  p = FluidParams{};
  p.burn_rate = -1.0;
  EXPECT_THROW(validate(p), std::invalid_argument);
}

}  // namespace
}  // namespace candela::fluid
