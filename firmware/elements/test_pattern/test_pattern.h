// The installer's test pattern (`candela --test-pattern`): colour bars, a
// frame counter and a marker crossing the screen every `period` seconds.
#pragma once

#include "scene/element.h"

namespace candela {

// Where the marker's left edge is, as a fraction of its travel, at a step.
// Shared with the tests so they know where to look.
inline double test_pattern_phase(uint64_t step, int steps_per_period) {
  return static_cast<double>(step % static_cast<uint64_t>(steps_per_period)) / steps_per_period;
}

const ElementKind& test_pattern_kind();

}  // namespace candela
