// The animation clock: time advances in fixed steps, counted as integers, so
// what is drawn depends only on the step count and the seed, never on how
// fast frames are presented.
#pragma once

#include <cstdint>

#include "core/fixed.h"

namespace candela {

class StepClock {
 public:
  explicit StepClock(int32_t steps_per_second = 60) : steps_per_second_(steps_per_second) {}

  int32_t steps_per_second() const { return steps_per_second_; }
  int64_t step_ns() const { return 1'000'000'000LL / steps_per_second_; }
  Fixed step_seconds() const { return Fixed::from_ratio(1, steps_per_second_); }
  uint64_t steps() const { return steps_; }
  // Seconds since start, exact for any step count below 2^15 s.
  Fixed seconds() const {
    return Fixed::from_raw(static_cast<int32_t>((static_cast<int64_t>(steps_) << Fixed::kFracBits) /
                                                steps_per_second_));
  }

  // Adds wall time and says how many whole steps are now due. Caps the
  // catch-up so a stall (e.g. a VT switch) does not replay minutes at once.
  int advance_wall(int64_t elapsed_ns, int max_steps = 8) {
    accumulator_ns_ += elapsed_ns;
    int due = 0;
    while (accumulator_ns_ >= step_ns() && due < max_steps) {
      accumulator_ns_ -= step_ns();
      ++due;
    }
    if (due == max_steps) accumulator_ns_ = 0;
    return due;
  }
  void tick() { ++steps_; }

 private:
  int32_t steps_per_second_;
  uint64_t steps_ = 0;
  int64_t accumulator_ns_ = 0;
};

}  // namespace candela
