// 2-D stable fluids (Stam 1999) for fire, after Kogawa, Dobashi and Yamamoto:
// semi-Lagrangian or MacCormack advection (Selle et al. 2008, clamped),
// fuel that burns to heat (Nguyen et al. 2002, simplified), buoyancy
// f = kappa_b (T - T_amb) y, vorticity
// confinement f = eps (N x omega) (Fedkiw et al. 2001), temperature carried by
// the flow and cooled by C_r ((T - T_amb) / (T_max - T_amb))^4, heat sources
// and an optional wind. Units: lengths in cells, time in seconds, temperature
// in kelvin. Staggered (MAC) grid: u on vertical faces, v on horizontal faces,
// T at cell centres; row 0 is the bottom.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/random.h"
#include "grid2.h"
#include "pressure_solver.h"

namespace candela::fluid {

struct HeatSource {
  double x = 0.5;               // centre, fraction of the grid width
  double y = 0.05;              // centre, fraction of the grid height (0 = bottom)
  double rx = 0.035;            // half-width, fraction of the grid width
  double ry = 0.025;            // half-height, fraction of the grid height
  double rate = 20000.0;        // heating at the centre, K/s
  double temperature = 1900.0;  // the source heats no higher than this, K
  double flicker = 0.3;         // depth of the slow random modulation of rate, 0..1
  double flicker_hz = 6.0;      // how often the modulation picks a new level
  double angle = 0.0;           // rotation of the ellipse, degrees (counter-clockwise)
  // Fuel (combustion): units of fuel per second injected at the centre; it
  // burns to heat where the air is above FluidParams::ignition. 0 = none.
  double fuel = 0.0;
  // Turbulent injection: depth (0..1) of a moving value noise of wavelength
  // `grain` cells that modulates heat and fuel along the emitter, so a log
  // feeds separate tongues instead of one sheet.
  double turbulence = 0.0;
  double grain = 6.0;
  double kick = 0.0;  // random velocity injected in the emitter, cells/s (turbulent inflow)
};

enum class Advection { kSemiLagrangian, kMacCormack };

// Wind speed (cells/s, + = to the right) as a piecewise-linear function of
// time; the force pulls the air toward it: f_x = drag (W(t) - u).
struct WindKey {
  double time = 0.0;
  double speed = 0.0;
};

struct FluidParams {
  int width = 128;
  int height = 128;
  Boundary boundary{};
  double t_ambient = 300.0;  // K
  double buoyancy = 0.05;    // kappa_b, cells/s^2 per K
  double vorticity = 0.6;    // eps, dimensionless in cell units
  double cooling = 6000.0;   // C_r, K/s
  // Mixing with the cold air a 2-D slice cannot entrain from the third
  // dimension: excess temperature also decays as exp(-mixing t). 0 = off
  // (the paper's radiative term alone). Without it, warm gas that has left
  // the flame fills the domain and drives domain-wide sway.
  double mixing = 0.0;  // 1/s
  double jitter = 0.5;  // per-cell random spread of source heating, 0..1
  Advection advection = Advection::kSemiLagrangian;
  // Combustion: fuel above `ignition` burns at `burn_rate` (fraction per
  // second, exact exponential decay over a step), each unit releasing
  // `heat_release` kelvin into its cell, up to `flame_temperature`.
  double burn_rate = 8.0;       // 1/s
  double ignition = 600.0;      // K
  double heat_release = 400.0;  // K per unit of fuel
  // Burning heats no cell above this (the adiabatic flame temperature: the
  // products of fuel and air can get no hotter), K.
  double flame_temperature = 2000.0;
  std::vector<HeatSource> sources;
  std::vector<WindKey> wind;         // empty = still air
  double wind_drag = 2.0;            // 1/s
  double pressure_tolerance = 1e-5;  // relative to the largest face speed
  int pressure_max_iterations = 200;
  uint64_t seed = 1;
};

// Throws std::invalid_argument naming the parameter and what it must be.
void validate(const FluidParams& p);
double wind_speed_at(const std::vector<WindKey>& keys, double t);

struct StepStats {
  PressureStats pressure;
  double max_speed = 0.0;
};

class FluidSolver {
 public:
  explicit FluidSolver(const FluidParams& params);

  // Advances by dt seconds (any dt > 0: semi-Lagrangian steps stay stable).
  StepStats step(double dt);

  double time() const { return time_; }
  const FluidParams& params() const { return params_; }
  int width() const { return params_.width; }
  int height() const { return params_.height; }

  // Fields, for tests and output. u: (w+1) x h, v: w x (h+1), T: w x h.
  Grid2& u() { return u_; }
  Grid2& v() { return v_; }
  Grid2& temperature() { return t_; }
  Grid2& fuel() { return f_; }
  const Grid2& fuel() const { return f_; }
  const Grid2& u() const { return u_; }
  const Grid2& v() const { return v_; }
  const Grid2& temperature() const { return t_; }

  // Velocity interpolated to cell centres (cells/s).
  void cell_velocity(Grid2& uc, Grid2& vc) const;
  // Net outflow of each cell per unit area (the discrete divergence, 1/s).
  void divergence(Grid2& out) const;
  double kinetic_energy() const;  // 0.5 sum |u|^2 over faces, cells^2 (cells/s)^2
  double max_temperature() const;
  // Mean |curl u| over the cells (1/s): what vorticity confinement feeds.
  double mean_abs_vorticity() const;

  // Makes the current velocity divergence-free (called by step()).
  PressureStats project();

 private:
  void add_heat(double dt);
  void advect(double dt);
  void burn(double dt);
  void cool(double dt);
  void add_forces(double dt);
  void enforce_walls();
  double source_modulation(size_t s);
  double sample_u(double x, double y) const { return u_.sample(x, y - 0.5); }
  double sample_v(double x, double y) const { return v_.sample(x - 0.5, y); }

  FluidParams params_;
  double time_ = 0.0;
  Grid2 u_, v_, t_, f_;
  Grid2 u_next_, v_next_, t_next_, f_next_;
  Grid2 u_back_, v_back_, t_back_, f_back_;  // MacCormack: the forward-then-back estimates
  Grid2 uc_, vc_, omega_, fx_, fy_;
  Grid2 rhs_, q_;
  PressureSolver pressure_;
  Pcg32 rng_;
  // Per source: the flicker knots (previous, next) and when the next is due.
  struct Flicker {
    double a = 0.0, b = 0.0, t0 = 0.0;
  };
  std::vector<Flicker> flicker_;
};

}  // namespace candela::fluid
