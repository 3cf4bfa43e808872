// One animation step as every element and the wind see it: the step's number,
// its length and time (fixed-point, so x86 and ARM agree) and the wind field.
// Here, below the scene, because the wind field reads it too (wind/ never
// includes scene/).
#pragma once

#include <cstdint>

#include "core/fixed.h"

namespace candela {

class WindField;

struct StepContext {
  uint64_t step = 0;  // steps since start
  Fixed dt;           // seconds per step
  Fixed time;         // seconds since start
  const WindField* wind = nullptr;
};

}  // namespace candela
