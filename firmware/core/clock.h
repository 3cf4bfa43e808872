// The animation clock: time advances in fixed steps, counted as integers, so
// what is drawn depends only on the step count and the seed, never on how
// fast frames are presented.
#pragma once

#include <time.h>

#include <atomic>
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

// The wall clock the kiosk's [schedule] follows (Unix time, ms). Injectable:
// the system's, a fake one tests set by hand, or a shifted and sped-up one
// (`candela --clock-start/--clock-scale`) to run a day's schedule in seconds.
class WallClock {
 public:
  virtual ~WallClock() = default;
  virtual int64_t now_ms() const = 0;
};

class SystemWallClock final : public WallClock {
 public:
  int64_t now_ms() const override {
    timespec ts{};
    clock_gettime(CLOCK_REALTIME, &ts);
    return int64_t{ts.tv_sec} * 1000 + ts.tv_nsec / 1'000'000;
  }
};

// Starts at `start_ms` and runs `scale` times as fast as the monotonic clock.
class ScaledWallClock final : public WallClock {
 public:
  ScaledWallClock(int64_t start_ms, double scale) : start_ms_(start_ms), scale_(scale) {
    clock_gettime(CLOCK_MONOTONIC, &t0_);
  }
  int64_t now_ms() const override {
    timespec ts{};
    clock_gettime(CLOCK_MONOTONIC, &ts);
    const double elapsed_ms = static_cast<double>(ts.tv_sec - t0_.tv_sec) * 1e3 +
                              static_cast<double>(ts.tv_nsec - t0_.tv_nsec) / 1e6;
    return start_ms_ + static_cast<int64_t>(elapsed_ms * scale_);
  }

 private:
  int64_t start_ms_;
  double scale_;
  timespec t0_{};
};

// Tests: whatever time it is told.
class FakeWallClock final : public WallClock {
 public:
  explicit FakeWallClock(int64_t ms = 0) : ms_(ms) {}
  int64_t now_ms() const override { return ms_.load(std::memory_order_relaxed); }
  void set_ms(int64_t ms) { ms_.store(ms, std::memory_order_relaxed); }
  void advance_ms(int64_t ms) { ms_.fetch_add(ms, std::memory_order_relaxed); }

 private:
  std::atomic<int64_t> ms_;
};

}  // namespace candela
