#include "elements/candle/candle_rig.h"

#include <algorithm>

#include "core/random.h"
#include "scene/element.h"
#include "wind/fixed_math.h"

namespace candela {
namespace {

Fixed rad(Fixed degrees) { return fixed_radians(degrees.to_double()); }
constexpr Fixed kOne = Fixed::from_int(1);
// 45 degrees: past it, turbulence moves split points along y instead of x.
constexpr Fixed kQuarterPi = Fixed::from_raw(51472);
constexpr Fixed kMaxLean = Fixed::from_raw(97264);  // 85 degrees

Fixed clamp_unit(Fixed v) { return clamp(v, -kOne, kOne); }

}  // namespace

ControlLines source_lines(const StillLayout& s) {
  ControlLines c;
  const Fixed h = s.tip - s.base;
  for (int j = 0; j < kTurbulenceSegments; ++j) {
    const Fixed y0 = s.base + h * j / kTurbulenceSegments;
    const Fixed y1 = s.base + h * (j + 1) / kTurbulenceSegments;
    c.line[j] = {{}, y0, {}, y1};
    c.line[kTurbulenceSegments + j] = {-s.half_width, y0, -s.half_width, y1};
    c.line[2 * kTurbulenceSegments + j] = {s.half_width, y0, s.half_width, y1};
  }
  // V3: from C0, a point in the flame's lower part, down to the base.
  c.line[kMaxControlLines - 1] = {{}, s.base + h / 4, {}, s.base};
  c.count = kMaxControlLines;
  return c;
}

CandleRig::CandleRig(const CandleParams& p, const StillLayout& layout, WindPosition position,
                     uint64_t seed)
    : layout_(layout), position_(position) {
  sway_ = {rad(p.sway_left), rad(p.sway_right)};
  tilt_ = {rad(p.tilt_front), rad(p.tilt_rear)};
  // lerp(high, low, N) as in the paper.
  calm_stretch_ = {p.calm_stretch_high, p.calm_stretch_low};
  calm_width_ = {p.calm_width_thick, p.calm_width_thin};
  breeze_stretch_ = {p.breeze_stretch_high, p.breeze_stretch_low};
  breeze_width_ = {p.breeze_width_thick, p.breeze_width_thin};
  // 1 for a flame of average calm size.
  brightness_norm_ =
      kOne / (((calm_stretch_.a + calm_stretch_.b) / 2) * ((calm_width_.a + calm_width_.b) / 2));
  lean_max_ = rad(p.lean);
  breeze_tilt_max_ = rad(p.breeze_tilt);
  flutter_ = p.flutter;
  inv_full_speed_ = kOne / p.full_speed;
  turbulence_ = p.turbulence;
  stick_angle_ = rad(p.stick_angle);
  wick_angle_ = rad(p.wick_angle);
  stick_depth_ = p.stick_depth;
  const Fixed omega = Fixed::from_double(2 * 3.14159265358979323846 * p.pendulum_hz.to_double());
  omega_sq_ = omega * omega;
  two_zeta_omega_ = p.pendulum_damping * omega * 2;
  extinguish_speed_ = p.extinguish_speed;
  relight_seconds_ = p.relight_seconds;
  regrow_seconds_ = p.regrow_seconds;
  turbulence_lag_ = p.turbulence_lag;
  flicker_ = p.flicker;
  calm_turbulence_ = p.calm_turbulence;
  bend_ = p.bend;
  Pcg32 rng(seed, 0x63616e646c65);
  for (int c = 0; c < kNoiseChannels; ++c) {
    const NoiseSource& n = p.noise[c];
    tables_[c] = n.table ? n.table.get() : &builtin_noise_table(n.beta, c);
    rates_[c] = n.rate;
    // Each candle starts somewhere else in every table.
    state_.phase[c] = rng.next_u32() & (tables_[c]->period_q16() - 1);
  }
  state_.stretch = calm_stretch_.a;
  state_.width = calm_width_.a;
  build_lines();
}

void CandleRig::update(const StepContext& step) {
  update(step.wind ? step.wind->sample(position_) : WindSample{}, step.dt);
}

void CandleRig::update(WindSample wind, Fixed dt) {
  CandleState& s = state_;
  Fixed n[kNoiseChannels];
  for (int c = 0; c < kNoiseChannels; ++c) {
    // Q16 samples per step = rate (samples/s) * dt (s).
    s.phase[c] += static_cast<uint32_t>((static_cast<int64_t>(rates_[c].raw) * dt.raw) >> 16);
    n[c] = tables_[c]->at(s.phase[c]);
  }

  // Wind: the pendulum chases the breeze amount on each axis, so after a
  // gust the flame swings past upright and settles, like a damped pendulum.
  const Fixed tx = clamp_unit(wind.x * inv_full_speed_);
  const Fixed tz = clamp_unit(wind.z * inv_full_speed_);
  s.vx += (omega_sq_ * (tx - s.ax) - two_zeta_omega_ * s.vx) * dt;
  s.ax += s.vx * dt;
  s.vz += (omega_sq_ * (tz - s.az) - two_zeta_omega_ * s.vz) * dt;
  s.az += s.vz * dt;
  s.strength = fixed_hypot(s.ax, s.az);
  if (s.strength > kOne) s.strength = kOne;

  // Calm (Table 1) plus light breeze (Table 2), the breeze weighted by strength.
  const Fixed calm_lean = lerp(sway_.a, sway_.b, n[kCalmSway]);
  const Fixed calm_tilt = lerp(tilt_.a, tilt_.b, n[kCalmTilt]);
  const Fixed shake_lr = lerp(kOne - flutter_, kOne, n[kBreezeLean]);
  const Fixed shake_fb = lerp(kOne - flutter_, kOne, n[kBreezeTilt]);
  s.lean = clamp(calm_lean + lean_max_ * clamp_unit(s.ax) * shake_lr, -kMaxLean, kMaxLean);
  s.tilt = clamp(calm_tilt + breeze_tilt_max_ * clamp_unit(s.az) * shake_fb, -kMaxLean, kMaxLean);
  s.stretch = lerp(lerp(calm_stretch_.a, calm_stretch_.b, n[kCalmStretch]),
                   lerp(breeze_stretch_.a, breeze_stretch_.b, n[kBreezeStretch]), s.strength);
  s.width = lerp(lerp(calm_width_.a, calm_width_.b, n[kCalmWidth]),
                 lerp(breeze_width_.a, breeze_width_.b, n[kBreezeWidth]), s.strength);
  // Turbulence D(t, i) = lerp(-Dmax, Dmax, N(t - i)): the same noise, later
  // for each point further up, so a disturbance travels up the flame.
  const uint32_t lag = static_cast<uint32_t>(
      (static_cast<int64_t>(rates_[kTurbulence].raw) * turbulence_lag_.raw) >> 16);
  // In still air a little of it stays: the outline never freezes.
  const Fixed turbulence_share = std::max(s.strength, calm_turbulence_);
  for (int i = 0; i < kTurbulenceSegments - 1; ++i) {
    const Fixed d = tables_[kTurbulence]->at(s.phase[kTurbulence] - lag * (i + 1));
    s.turbulence[i] = lerp(-turbulence_, turbulence_, d) * turbulence_share;
  }
  s.tip = lerp(-flicker_, flicker_, n[kCalmFlicker]);
  s.stuck = abs(s.lean - wick_angle_) > stick_angle_;

  // Blowing out and relighting.
  s.wind_speed = fixed_hypot(wind.x, wind.z);
  const int32_t sps = dt.raw > 0 ? (Fixed::kOne + dt.raw / 2) / dt.raw : 60;
  if (s.lit && s.wind_speed > extinguish_speed_) {
    s.lit = false;
    s.out_steps = 0;
    s.relight_in = static_cast<int32_t>(steps_in(relight_seconds_, sps));
    s.grow = Fixed{};
    ++s.times_out;
  } else if (!s.lit) {
    ++s.out_steps;
    if (s.relight_in > 0) --s.relight_in;
    if (s.relight_in == 0 && s.wind_speed * 2 < extinguish_speed_) {
      s.lit = true;
      s.out_steps = -1;
    }
  } else if (s.grow < kOne) {
    s.grow += dt / regrow_seconds_;
    if (s.grow > kOne) s.grow = kOne;
  }
  build_lines();
}

void CandleRig::build_lines() {
  const CandleState& s = state_;
  const StillLayout& L = layout_;
  const Fixed sn = fixed_sin(s.lean), cs = fixed_cos(s.lean);
  const Fixed h = (L.tip - L.base) * s.stretch;
  const Fixed hw = L.half_width * s.width;
  // Up along the leaning flame, and across it.
  const Fixed ux = sn, uy = cs, rx = cs, ry = -sn;
  Fixed cx[kTurbulenceSegments + 1], cy[kTurbulenceSegments + 1];
  const bool upright = abs(s.lean) < kQuarterPi;
  // The flame bends along its length: each segment leans by its own angle,
  // the lean's share growing towards the tip (the base stays on the wick),
  // so the tip streams downwind. The tip segment also flickers in length.
  cx[0] = Fixed{};
  cy[0] = L.base;
  const Fixed segment = h / kTurbulenceSegments;
  for (int k = 1; k <= kTurbulenceSegments; ++k) {
    const Fixed share =
        kOne + bend_ * (2 * k - 1 - kTurbulenceSegments) / (kTurbulenceSegments - 1);
    const Fixed a = clamp(s.lean * share, -kMaxLean, kMaxLean);
    const Fixed len = k == kTurbulenceSegments ? segment + h * s.tip : segment;
    cx[k] = cx[k - 1] + fixed_sin(a) * len;
    cy[k] = cy[k - 1] + fixed_cos(a) * len;
  }
  for (int k = 0; k <= kTurbulenceSegments; ++k) {
    if (k > 0 && k < kTurbulenceSegments) {
      // Eq. (3): across a mostly upright flame, else along y.
      if (upright)
        cx[k] += s.turbulence[k - 1];
      else
        cy[k] += s.turbulence[k - 1];
    }
  }
  ControlLines& c = lines_;
  for (int j = 0; j < kTurbulenceSegments; ++j) {
    c.line[j] = {cx[j], cy[j], cx[j + 1], cy[j + 1]};
    c.line[kTurbulenceSegments + j] = {cx[j] - rx * hw, cy[j] - ry * hw, cx[j + 1] - rx * hw,
                                       cy[j + 1] - ry * hw};
    c.line[2 * kTurbulenceSegments + j] = {cx[j] + rx * hw, cy[j] + ry * hw, cx[j + 1] + rx * hw,
                                           cy[j + 1] + ry * hw};
  }
  if (s.stuck) {
    // The roots of V1 and V2 cling to the wick top; V3 pulls the lower flame
    // from C0 down to C1 on the wick.
    c.line[kTurbulenceSegments].px = c.line[2 * kTurbulenceSegments].px = Fixed{};
    c.line[kTurbulenceSegments].py = c.line[2 * kTurbulenceSegments].py = L.base;
    const Fixed c0 = h / 4;
    c.line[kMaxControlLines - 1] = {ux * c0, L.base + uy * c0,
                                    -fixed_sin(wick_angle_) * stick_depth_,
                                    L.base - fixed_cos(wick_angle_) * stick_depth_};
    c.count = kMaxControlLines;
  } else {
    c.line[kMaxControlLines - 1] = {};
    c.count = kMaxControlLines - 1;
  }
}

Fixed CandleRig::brightness() const {
  if (!state_.lit) return Fixed{};
  return state_.stretch * state_.width * state_.grow * brightness_norm_;
}

}  // namespace candela
