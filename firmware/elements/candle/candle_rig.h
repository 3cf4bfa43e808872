// One candle's flame motion (the paper's noise-based morphing, animation
// half): 1/f^beta noise tables drive the control lines V0..V3 of a
// Beier-Neely warp, the wind at the candle adds lean, tilt, stretch,
// turbulence and wick sticking, a pendulum carries the flame back to calm,
// and strong wind blows it out. Fixed-point and allocation-free: the same
// seed gives the same state, bit for bit, on any CPU.
#pragma once

#include <array>
#include <cstdint>

#include "core/fixed.h"
#include "elements/candle/candle_params.h"
#include "wind/wind_field.h"

namespace candela {

struct StepContext;

// A control line P -> Q in billboard units (see StillLayout).
struct ControlLine {
  Fixed px, py, qx, qy;
  bool operator==(const ControlLine&) const = default;
};

// V0 (centre), V1 (left), V2 (right), each split into 3 segments by the
// turbulence, and V3 (wick sticking): lines 0-2 are V0, 3-5 V1, 6-8 V2, 9 V3.
inline constexpr int kTurbulenceSegments = 3;
inline constexpr int kMaxControlLines = 3 * kTurbulenceSegments + 1;
struct ControlLines {
  std::array<ControlLine, kMaxControlLines> line{};
  int count = 3 * kTurbulenceSegments;  // 10 while the flame sticks to the wick
  bool operator==(const ControlLines&) const = default;
};

// The lines on the still itself (all 10; V3 runs from C0 down to the base).
ControlLines source_lines(const StillLayout& layout);

struct CandleState {
  std::array<uint32_t, kNoiseChannels> phase{};  // Q16.16 table positions
  Fixed ax, vx, az, vz;  // pendulum: breeze amount (-1..1) left-right, front-back, and rates
  Fixed lean;            // left-right lean of V0 from vertical, radians (+: toward +x)
  Fixed tilt;            // front-back billboard rotation, radians (+: toward the viewer)
  Fixed stretch, width;  // vertical and horizontal stretch ratios
  Fixed strength;        // how much of the breeze deformation applies, 0..1
  std::array<Fixed, kTurbulenceSegments - 1> turbulence{};  // D at the split points
  Fixed tip;                                                // tip flicker, flame lengths
  Fixed grow = Fixed::from_int(1);                          // flame size while relighting, 0..1
  Fixed wind_speed;                                         // |wind| here, m/s
  int32_t out_steps = -1;                                   // steps since it went out; -1 while lit
  int32_t relight_in = 0;                                   // steps until it may relight
  uint32_t times_out = 0;
  bool lit = true;
  bool stuck = false;  // the flame clings to the wick
  bool operator==(const CandleState&) const = default;
};

class CandleRig {
 public:
  CandleRig(const CandleParams& params, const StillLayout& layout, WindPosition position,
            uint64_t seed);
  // One fixed step; the wind comes from step.wind (calm if none).
  void update(const StepContext& step);
  void update(WindSample wind, Fixed dt);

  const CandleState& state() const { return state_; }
  const ControlLines& lines() const { return lines_; }
  WindPosition position() const { return position_; }
  // Flame size relative to the calm average: drives glow, wax light and colour.
  Fixed brightness() const;
  // Lean/tilt limits in radians, for checks.
  Fixed stick_angle() const { return stick_angle_; }
  Fixed wick_angle() const { return wick_angle_; }

 private:
  void build_lines();

  // Parameters in the units the step uses (radians, Q16 rates).
  struct Range {
    Fixed a, b;
  };
  Range sway_, tilt_, calm_stretch_, calm_width_, breeze_stretch_, breeze_width_;
  Fixed lean_max_, breeze_tilt_max_, flutter_, inv_full_speed_, turbulence_;
  Fixed stick_angle_, wick_angle_, stick_depth_;
  Fixed omega_sq_, two_zeta_omega_;
  Fixed extinguish_speed_, relight_seconds_, regrow_seconds_;
  Fixed turbulence_lag_;
  Fixed flicker_, calm_turbulence_, bend_;
  Fixed brightness_norm_;
  std::array<const NoiseTable*, kNoiseChannels> tables_{};
  std::array<Fixed, kNoiseChannels> rates_{};
  StillLayout layout_;
  WindPosition position_;
  CandleState state_;
  ControlLines lines_;
};

}  // namespace candela
