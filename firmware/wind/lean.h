// A flame leaning with the wind it feels, one fixed step at a time (the
// eigen-flame's lean, the perlin fire's tip): the lean it should show is the
// wind times its lean per m/s, within +-max; it follows that with a
// first-order lag of `response` (1/s).
#pragma once

#include <algorithm>

#include "core/fixed.h"

namespace candela {

// How far the lag moves in one step of `dt`: dt * response of the way, at most all of it.
constexpr Fixed lag_gain(Fixed dt, Fixed response) {
  return std::min(Fixed::from_int(1), dt * response);
}

// One step of the lean toward what `wind` (m/s) asks for, by `gain` (lag_gain) of the way.
constexpr Fixed lean_toward(Fixed lean, Fixed wind, Fixed lean_per_speed, Fixed max_lean,
                            Fixed gain) {
  return lerp(lean, clamp(wind * lean_per_speed, -max_lean, max_lean), gain);
}

}  // namespace candela
