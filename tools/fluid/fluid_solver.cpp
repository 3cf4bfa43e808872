#include "fluid_solver.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "lattice_noise.h"

namespace candela::fluid {
namespace {

[[noreturn]] void bad(const std::string& what, const std::string& expected) {
  throw std::invalid_argument(what + ": " + expected);
}

bool finite(double v) { return std::isfinite(v); }

}  // namespace

void validate(const FluidParams& p) {
  if (p.width < 8 || p.width > 2048) bad("width", "an integer in 8..2048");
  if (p.height < 8 || p.height > 2048) bad("height", "an integer in 8..2048");
  if (std::max(p.width, p.height) > 16 * std::min(p.width, p.height))
    bad("grid", "an aspect ratio of at most 16:1");
  if (!p.boundary.any_open()) bad("boundary", "at least one open side");
  if (!finite(p.t_ambient) || p.t_ambient <= 0.0) bad("t-ambient", "a temperature > 0 K");
  if (!finite(p.buoyancy) || p.buoyancy < 0.0) bad("buoyancy", "a number >= 0");
  if (!finite(p.vorticity) || p.vorticity < 0.0) bad("vorticity", "a number >= 0");
  if (!finite(p.cooling) || p.cooling < 0.0) bad("cooling", "a number >= 0 (K/s)");
  if (!finite(p.mixing) || p.mixing < 0.0 || p.mixing > 1000.0)
    bad("mixing", "a rate in 0..1000 per second");
  if (!finite(p.jitter) || p.jitter < 0.0 || p.jitter > 1.0) bad("jitter", "a number in 0..1");
  if (!finite(p.wind_drag) || p.wind_drag < 0.0) bad("wind-drag", "a number >= 0 (1/s)");
  if (!finite(p.pressure_tolerance) || p.pressure_tolerance <= 0.0 || p.pressure_tolerance > 0.1)
    bad("pressure-tolerance", "a number in (0, 0.1]");
  if (p.pressure_max_iterations < 1) bad("pressure-iterations", "an integer >= 1");
  if (!finite(p.burn_rate) || p.burn_rate < 0.0 || p.burn_rate > 1e4)
    bad("burn-rate", "a rate in 0..10000 per second");
  if (!finite(p.ignition) || p.ignition < 0.0) bad("ignition", "a temperature >= 0 K");
  if (!finite(p.flame_temperature) || p.flame_temperature <= p.t_ambient)
    bad("flame-temperature", "a temperature above the ambient temperature");
  if (!finite(p.heat_release) || p.heat_release < 0.0 || p.heat_release > 1e5)
    bad("heat-release", "kelvin per unit of fuel in 0..100000");
  for (size_t k = 0; k < p.sources.size(); ++k) {
    const HeatSource& s = p.sources[k];
    const std::string n = "source " + std::to_string(k + 1);
    if (!finite(s.x) || s.x < 0.0 || s.x > 1.0) bad(n + " x", "a fraction of the width in 0..1");
    if (!finite(s.y) || s.y < 0.0 || s.y > 1.0) bad(n + " y", "a fraction of the height in 0..1");
    if (!finite(s.rx) || s.rx <= 0.0 || s.rx > 1.0) bad(n + " rx", "a fraction in (0, 1]");
    if (!finite(s.ry) || s.ry <= 0.0 || s.ry > 1.0) bad(n + " ry", "a fraction in (0, 1]");
    if (!finite(s.rate) || s.rate < 0.0) bad(n + " rate", "a heating rate >= 0 K/s");
    if (!finite(s.temperature) || s.temperature <= p.t_ambient)
      bad(n + " temp", "a temperature above the ambient temperature");
    if (!finite(s.flicker) || s.flicker < 0.0 || s.flicker > 1.0)
      bad(n + " flicker", "a number in 0..1");
    if (!finite(s.flicker_hz) || s.flicker_hz <= 0.0 || s.flicker_hz > 1000.0)
      bad(n + " flicker-hz", "a frequency in (0, 1000]");
    if (!finite(s.angle) || std::fabs(s.angle) > 360.0) bad(n + " angle", "degrees in -360..360");
    if (!finite(s.fuel) || s.fuel < 0.0) bad(n + " fuel", "a fuel rate >= 0 per second");
    if (!finite(s.turbulence) || s.turbulence < 0.0 || s.turbulence > 1.0)
      bad(n + " turbulence", "a number in 0..1");
    if (!finite(s.grain) || s.grain < 1.0 || s.grain > 4096.0)
      bad(n + " grain", "a noise wavelength in 1..4096 cells");
    if (!finite(s.kick) || s.kick < 0.0 || s.kick > 10000.0)
      bad(n + " kick", "a speed in 0..10000 cells/s");
  }
  for (size_t k = 0; k < p.wind.size(); ++k) {
    if (!finite(p.wind[k].time) || !finite(p.wind[k].speed)) bad("wind", "finite TIME:SPEED pairs");
    if (k > 0 && !(p.wind[k].time > p.wind[k - 1].time))
      bad("wind", "TIME:SPEED pairs with strictly increasing times");
  }
}

double wind_speed_at(const std::vector<WindKey>& keys, double t) {
  if (keys.empty()) return 0.0;
  if (t <= keys.front().time) return keys.front().speed;
  if (t >= keys.back().time) return keys.back().speed;
  for (size_t k = 1; k < keys.size(); ++k) {
    if (t <= keys[k].time) {
      const double f = (t - keys[k - 1].time) / (keys[k].time - keys[k - 1].time);
      return keys[k - 1].speed + (keys[k].speed - keys[k - 1].speed) * f;
    }
  }
  return keys.back().speed;
}

FluidSolver::FluidSolver(const FluidParams& params)
    : params_((validate(params), params)),
      u_(params.width + 1, params.height),
      v_(params.width, params.height + 1),
      t_(params.width, params.height, params.t_ambient),
      f_(params.width, params.height),
      u_next_(params.width + 1, params.height),
      v_next_(params.width, params.height + 1),
      t_next_(params.width, params.height),
      f_next_(params.width, params.height),
      uc_(params.width, params.height),
      vc_(params.width, params.height),
      omega_(params.width, params.height),
      fx_(params.width, params.height),
      fy_(params.width, params.height),
      rhs_(params.width, params.height),
      q_(params.width, params.height),
      pressure_(params.width, params.height, params.boundary),
      rng_(params.seed, 0x5eed) {
  flicker_.resize(params_.sources.size());
  for (auto& f : flicker_) {
    f.a = rng_.unit_double() * 2.0 - 1.0;
    f.b = rng_.unit_double() * 2.0 - 1.0;
  }
}

// Slow random modulation in [-1, 1]: straight lines between random levels
// drawn flicker_hz times a second, so a flame breathes instead of buzzing.
double FluidSolver::source_modulation(size_t s) {
  const double period = 1.0 / params_.sources[s].flicker_hz;
  Flicker& f = flicker_[s];
  while (time_ >= f.t0 + period) {
    f.t0 += period;
    f.a = f.b;
    f.b = rng_.unit_double() * 2.0 - 1.0;
  }
  return f.a + (f.b - f.a) * ((time_ - f.t0) / period);
}

void FluidSolver::add_heat(double dt) {
  const int w = params_.width, h = params_.height;
  for (size_t s = 0; s < params_.sources.size(); ++s) {
    const HeatSource& src = params_.sources[s];
    const double mod = std::max(0.0, 1.0 + src.flicker * source_modulation(s));
    const double cx = src.x * w, cy = src.y * h;
    const double rx = std::max(src.rx * w, 0.5), ry = std::max(src.ry * h, 0.5);
    const double a = src.angle * (std::numbers::pi / 180.0), ca = std::cos(a), sa = std::sin(a);
    // Bounding box of the (rotated) ellipse.
    const double bx = std::hypot(rx * ca, ry * sa), by = std::hypot(rx * sa, ry * ca);
    const int i0 = std::max(0, static_cast<int>(std::floor(cx - bx)));
    const int i1 = std::min(w - 1, static_cast<int>(std::ceil(cx + bx)));
    const int j0 = std::max(0, static_cast<int>(std::floor(cy - by)));
    const int j1 = std::min(h - 1, static_cast<int>(std::ceil(cy + by)));
    const double span = src.temperature - params_.t_ambient;
    const uint64_t nseed = mix64(params_.seed * 0x100000001b3ull + s);
    // The noise drifts upward with time and changes ~2x per flicker period,
    // so the emitter feeds tongues that come and go.
    const double nt = time_ * src.flicker_hz * 2.0;
    const double relax = 1.0 - std::exp(-20.0 * dt);
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) {
        const double px = i + 0.5 - cx, py = j + 0.5 - cy;
        const double dx = (ca * px + sa * py) / rx, dy = (-sa * px + ca * py) / ry;
        const double g = 1.0 - (dx * dx + dy * dy);
        if (g <= 0.0) continue;
        const double noise = 1.0 + params_.jitter * (2.0 * rng_.unit_double() - 1.0);
        double turb = 1.0;
        if (src.turbulence > 0.0) {
          const double n = value_noise(nseed, (i + 0.5) / src.grain, (j + 0.5) / src.grain, nt);
          // Sharpened: mostly fed or mostly starved, few half-fed places.
          const double e = std::clamp((n - 0.5) * 2.5 + 0.5, 0.0, 1.0);
          turb = std::max(0.0, 1.0 - src.turbulence + src.turbulence * 2.0 * e);
        }
        const double amount = g * mod * noise * turb;
        if (src.fuel > 0.0) f_.at(i, j) += src.fuel * amount * dt;
        if (src.kick > 0.0) {
          const double nu =
              value_noise(nseed ^ 0x75ull, (i + 0.5) / src.grain, j / src.grain, nt * 1.7) - 0.5;
          const double nv =
              value_noise(nseed ^ 0x76ull, i / src.grain, (j + 0.5) / src.grain, nt * 1.7);
          const double k = relax * std::min(1.0, 2.0 * g);
          // Mostly upward, a little sideways: the gas leaves the fuel bed rising.
          u_.at(i, j) += (0.6 * src.kick * nu - u_.at(i, j)) * k;
          v_.at(i, j) += (src.kick * (0.5 + nv) - v_.at(i, j)) * k;
        }
        double& t = t_.at(i, j);
        if (t >= src.temperature || src.rate <= 0.0) continue;
        // Heating slows as the cell nears the source temperature; solved
        // exactly over the step, so no dt overshoots it.
        const double lambda = src.rate * amount / span;
        t = src.temperature - (src.temperature - t) * std::exp(-lambda * dt);
      }
  }
}

void FluidSolver::advect(double dt) {
  const int w = params_.width, h = params_.height;
  const bool mac = params_.advection == Advection::kMacCormack;
  const bool fuel = f_.max_abs() > 0.0;
  // Second-order (midpoint) trace through the current velocity, `d` seconds
  // back (d < 0: forward, for MacCormack's reverse step).
  auto trace = [&](double x, double y, double d, double& sx, double& sy) {
    const double mx = x - 0.5 * d * sample_u(x, y), my = y - 0.5 * d * sample_v(x, y);
    sx = x - d * sample_u(mx, my);
    sy = y - d * sample_v(mx, my);
  };
  // One semi-Lagrangian pass of `src` (a lattice offset ox, oy from the
  // cell corner) into `dst`.
  auto pass = [&](const Grid2& src, Grid2& dst, double ox, double oy, double d) {
    double sx = 0.0, sy = 0.0;
    for (int j = 0; j < dst.height; ++j)
      for (int i = 0; i < dst.width; ++i) {
        trace(i + ox, j + oy, d, sx, sy);
        dst.at(i, j) = src.sample(sx - ox, sy - oy);
      }
  };
  // MacCormack (Selle et al. 2008): forward pass q^ = A(q), reverse pass
  // q~ = A^-1(q^); q^ + (q - q~)/2 cancels the first-order error. Clamped to
  // the values the forward pass blended, so it is as stable as one pass.
  auto advect_one = [&](Grid2& q, Grid2& next, Grid2& back, double ox, double oy) {
    pass(q, next, ox, oy, dt);
    if (!mac) return;
    if (back.width != q.width || back.height != q.height) back = Grid2(q.width, q.height);
    pass(next, back, ox, oy, -dt);
    double sx = 0.0, sy = 0.0, lo = 0.0, hi = 0.0;
    for (int j = 0; j < q.height; ++j)
      for (int i = 0; i < q.width; ++i) {
        trace(i + ox, j + oy, dt, sx, sy);
        q.sample_range(sx - ox, sy - oy, lo, hi);
        const double c = next.at(i, j) + 0.5 * (q.at(i, j) - back.at(i, j));
        next.at(i, j) = std::clamp(c, lo, hi);
      }
  };
  (void)w;
  (void)h;
  advect_one(u_, u_next_, u_back_, 0.0, 0.5);
  advect_one(v_, v_next_, v_back_, 0.5, 0.0);
  advect_one(t_, t_next_, t_back_, 0.5, 0.5);
  if (fuel) advect_one(f_, f_next_, f_back_, 0.5, 0.5);
  std::swap(u_, u_next_);
  std::swap(v_, v_next_);
  std::swap(t_, t_next_);
  if (fuel) std::swap(f_, f_next_);
}

// Fuel above the ignition temperature burns at burn_rate: over a step a share
// 1 - exp(-burn_rate dt) of it goes, and each unit burnt heats the cell by
// heat_release kelvin, up to flame_temperature. Below that, fuel x
// heat_release + T is conserved.
void FluidSolver::burn(double dt) {
  if (params_.burn_rate <= 0.0) return;
  const double share = 1.0 - std::exp(-params_.burn_rate * dt);
  for (size_t k = 0; k < f_.data.size(); ++k) {
    double& f = f_.data[k];
    if (f <= 0.0 || t_.data[k] <= params_.ignition) continue;
    const double b = f * share;
    f -= b;
    double& t = t_.data[k];
    t = std::max(t, std::min(t + params_.heat_release * b, params_.flame_temperature));
  }
}

// dT/dt = -C_r s^4, s = (T - T_amb)/(T_max - T_amb), T_max the hottest cell.
// The hottest cell has s = 1, so its excess m falls linearly: m1 = m0 - C_r dt;
// every other excess x then obeys dx/dt = -C_r x^4 / m(t)^4, which separates:
// 1/x1^3 = 1/x0^3 + 1/m1^3 - 1/m0^3. Exact over any dt, so no step can
// overshoot ambient. Cells colder than ambient warm back the same way (m is
// then the largest |T - T_amb|: the same thing when everything is hot).
void FluidSolver::cool(double dt) {
  const double amb = params_.t_ambient;
  if (params_.mixing > 0.0) {
    const double keep = std::exp(-params_.mixing * dt);
    for (double& t : t_.data) t = amb + (t - amb) * keep;
  }
  if (params_.cooling <= 0.0) return;
  double m0 = 0.0;
  for (double t : t_.data) m0 = std::max(m0, std::fabs(t - amb));
  if (m0 <= 0.0) return;
  const double m1 = m0 - params_.cooling * dt;
  if (m1 <= 0.0) {  // the hottest cell reaches ambient, and all the others with it
    t_.fill(amb);
    return;
  }
  const double shift = 1.0 / (m1 * m1 * m1) - 1.0 / (m0 * m0 * m0);
  for (double& t : t_.data) {
    const double x0 = t - amb;
    const double a = std::fabs(x0);
    if (a == 0.0) continue;
    const double x1 = 1.0 / std::cbrt(1.0 / (a * a * a) + shift);
    t = amb + (x0 < 0.0 ? -x1 : x1);
  }
}

void FluidSolver::add_forces(double dt) {
  const int w = params_.width, h = params_.height;
  const double amb = params_.t_ambient;
  // Buoyancy on horizontal faces, from the two cells they separate.
  if (params_.buoyancy > 0.0) {
    for (int j = 0; j <= h; ++j)
      for (int i = 0; i < w; ++i) {
        const double tf = 0.5 * (t_.clamped(i, j - 1) + t_.clamped(i, j));
        v_.at(i, j) += dt * params_.buoyancy * (tf - amb);
      }
  }
  if (params_.vorticity > 0.0) {
    cell_velocity(uc_, vc_);
    for (int j = 0; j < h; ++j)
      for (int i = 0; i < w; ++i)
        omega_.at(i, j) = 0.5 * (vc_.clamped(i + 1, j) - vc_.clamped(i - 1, j)) -
                          0.5 * (uc_.clamped(i, j + 1) - uc_.clamped(i, j - 1));
    for (int j = 0; j < h; ++j)
      for (int i = 0; i < w; ++i) {
        const double gx =
            0.5 * (std::fabs(omega_.clamped(i + 1, j)) - std::fabs(omega_.clamped(i - 1, j)));
        const double gy =
            0.5 * (std::fabs(omega_.clamped(i, j + 1)) - std::fabs(omega_.clamped(i, j - 1)));
        const double len = std::sqrt(gx * gx + gy * gy) + 1e-12;
        const double nx = gx / len, ny = gy / len, om = omega_.at(i, j);
        // N x omega with omega along z: (N_y omega, -N_x omega).
        fx_.at(i, j) = params_.vorticity * ny * om;
        fy_.at(i, j) = -params_.vorticity * nx * om;
      }
    for (int j = 0; j < h; ++j)
      for (int i = 0; i <= w; ++i)
        u_.at(i, j) += dt * 0.5 * (fx_.clamped(i - 1, j) + fx_.clamped(i, j));
    for (int j = 0; j <= h; ++j)
      for (int i = 0; i < w; ++i)
        v_.at(i, j) += dt * 0.5 * (fy_.clamped(i, j - 1) + fy_.clamped(i, j));
  }
  if (!params_.wind.empty() && params_.wind_drag > 0.0) {
    // Relaxation toward the wind speed, solved exactly over the step.
    const double wind = wind_speed_at(params_.wind, time_);
    const double keep = std::exp(-params_.wind_drag * dt);
    for (double& u : u_.data) u = wind + (u - wind) * keep;
  }
}

void FluidSolver::enforce_walls() {
  const int w = params_.width, h = params_.height;
  const Boundary& b = params_.boundary;
  for (int j = 0; j < h; ++j) {
    if (!b.open_left) u_.at(0, j) = 0.0;
    if (!b.open_right) u_.at(w, j) = 0.0;
  }
  for (int i = 0; i < w; ++i) {
    if (!b.open_bottom) v_.at(i, 0) = 0.0;
    if (!b.open_top) v_.at(i, h) = 0.0;
  }
}

PressureStats FluidSolver::project() {
  const int w = params_.width, h = params_.height;
  enforce_walls();
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i)
      rhs_.at(i, j) = -(u_.at(i + 1, j) - u_.at(i, j) + v_.at(i, j + 1) - v_.at(i, j));
  const double scale = std::max(std::max(u_.max_abs(), v_.max_abs()), 1e-9);
  const PressureStats st = pressure_.solve(rhs_, q_, params_.pressure_tolerance * scale,
                                           params_.pressure_max_iterations);
  const Boundary& b = params_.boundary;
  for (int j = 0; j < h; ++j)
    for (int i = 0; i <= w; ++i) {
      if ((i == 0 && !b.open_left) || (i == w && !b.open_right)) continue;
      const double right = i < w ? q_.at(i, j) : 0.0;
      const double left = i > 0 ? q_.at(i - 1, j) : 0.0;
      u_.at(i, j) -= right - left;
    }
  for (int j = 0; j <= h; ++j)
    for (int i = 0; i < w; ++i) {
      if ((j == 0 && !b.open_bottom) || (j == h && !b.open_top)) continue;
      const double up = j < h ? q_.at(i, j) : 0.0;
      const double down = j > 0 ? q_.at(i, j - 1) : 0.0;
      v_.at(i, j) -= up - down;
    }
  return st;
}

StepStats FluidSolver::step(double dt) {
  if (!(dt > 0.0) || !std::isfinite(dt)) throw std::invalid_argument("dt: a time step > 0 s");
  StepStats st;
  add_heat(dt);
  advect(dt);
  burn(dt);
  cool(dt);
  add_forces(dt);
  st.pressure = project();
  st.max_speed = std::max(u_.max_abs(), v_.max_abs());
  time_ += dt;
  return st;
}

void FluidSolver::cell_velocity(Grid2& uc, Grid2& vc) const {
  const int w = params_.width, h = params_.height;
  if (uc.width != w || uc.height != h) uc = Grid2(w, h);
  if (vc.width != w || vc.height != h) vc = Grid2(w, h);
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      uc.at(i, j) = 0.5 * (u_.at(i, j) + u_.at(i + 1, j));
      vc.at(i, j) = 0.5 * (v_.at(i, j) + v_.at(i, j + 1));
    }
}

void FluidSolver::divergence(Grid2& out) const {
  const int w = params_.width, h = params_.height;
  if (out.width != w || out.height != h) out = Grid2(w, h);
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i)
      out.at(i, j) = u_.at(i + 1, j) - u_.at(i, j) + v_.at(i, j + 1) - v_.at(i, j);
}

double FluidSolver::kinetic_energy() const {
  double e = 0.0;
  for (double x : u_.data) e += x * x;
  for (double x : v_.data) e += x * x;
  return 0.5 * e;
}

double FluidSolver::mean_abs_vorticity() const {
  const int w = params_.width, h = params_.height;
  double sum = 0.0;
  // Curl at cell centres from the face velocities around each cell.
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      auto vc = [&](int a, int b) {
        a = std::clamp(a, 0, w - 1);
        b = std::clamp(b, 0, h - 1);
        return 0.5 * (v_.at(a, b) + v_.at(a, b + 1));
      };
      auto uc = [&](int a, int b) {
        a = std::clamp(a, 0, w - 1);
        b = std::clamp(b, 0, h - 1);
        return 0.5 * (u_.at(a, b) + u_.at(a + 1, b));
      };
      sum += std::fabs(0.5 * (vc(i + 1, j) - vc(i - 1, j)) - 0.5 * (uc(i, j + 1) - uc(i, j - 1)));
    }
  return sum / (static_cast<double>(w) * h);
}

double FluidSolver::max_temperature() const {
  double m = params_.t_ambient;
  for (double t : t_.data) m = std::max(m, t);
  return m;
}

}  // namespace candela::fluid
