// The 2-D fire solver: incompressibility, buoyancy, cooling, stability and
// determinism, each checked against what the equations predict.
#include "fluid_solver.h"

#include <gtest/gtest.h>

#include <cmath>

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
}

}  // namespace
}  // namespace candela::fluid
