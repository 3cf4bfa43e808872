// When random sound events happen: a Poisson process with a rate that may
// change every step, drawn in integers (PCG32), so the event times are the
// same on any CPU. Each step is cut into slots of kSlotSamples; a slot holds
// an event with probability rate * slot length (a Bernoulli process, which
// approaches Poisson for the small probabilities used: at 200/s, 0.07).
#pragma once

#include <cstdint>

#include "core/fixed.h"
#include "core/random.h"

namespace candela {

class EventClock {
 public:
  static constexpr int kSlotSamples = 16;  // 1/3 ms at 48 kHz

  explicit EventClock(uint64_t seed, uint64_t stream) : rng_(seed, stream) {}

  // Sets the rate (events per second, Q16.16; capped at 3000/s, one per slot).
  void set_rate(Fixed per_second) {
    const int64_t raw = per_second.raw < 0 ? 0 : per_second.raw;
    // P(slot) * 2^32 = rate * slot / 48000 * 2^32 = raw * 16 * 2^16 / 48000.
    const int64_t t = raw * kSlotSamples * 65536 / 48000;
    threshold_ = static_cast<uint32_t>(t > 0xffffffffLL ? 0xffffffffLL : t);
  }
  // Calls on_event(sample offset) for each event in [0, samples). Slots run
  // on across steps, so any step length keeps the rate exact.
  template <typename F>
  void run(int samples, F&& on_event) {
    for (; next_slot_ < samples; next_slot_ += kSlotSamples) {
      if (threshold_ == 0) continue;
      if (rng_.next_u32() < threshold_) {
        const int at = next_slot_ + static_cast<int>(rng_.next_u32() % kSlotSamples);
        on_event(at < samples ? at : samples - 1);
      }
    }
    next_slot_ -= samples;
  }

 private:
  Pcg32 rng_;
  uint32_t threshold_ = 0;
  int next_slot_ = 0;  // where the next slot starts, samples into the coming step
};

}  // namespace candela
