// Seeded, platform-independent random numbers (PCG32, O'Neill 2014). The
// standard library's distributions differ between implementations, so every
// draw used by animation goes through here.
#pragma once

#include <cstdint>

#include "core/fixed.h"

namespace candela {

class Pcg32 {
 public:
  explicit Pcg32(uint64_t seed, uint64_t stream = 54) {
    inc_ = (stream << 1u) | 1u;
    next_u32();
    state_ += seed;
    next_u32();
  }
  uint32_t next_u32() {
    const uint64_t old = state_;
    state_ = old * 6364136223846793005ULL + inc_;
    const auto xorshifted = static_cast<uint32_t>(((old >> 18u) ^ old) >> 27u);
    const auto rot = static_cast<uint32_t>(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((32 - rot) & 31));
  }
  // Uniform in [0, bound) without modulo bias.
  uint32_t below(uint32_t bound) {
    const uint32_t threshold = (0u - bound) % bound;
    for (;;) {
      const uint32_t r = next_u32();
      if (r >= threshold) return r % bound;
    }
  }
  // Uniform in [0, 1) as Q16.16.
  Fixed unit() { return Fixed::from_raw(static_cast<int32_t>(next_u32() >> 16)); }
  // Uniform in [0, 1) as double, for offline tools only.
  double unit_double() { return (next_u32() >> 5) * (1.0 / 134217728.0); }

 private:
  uint64_t state_ = 0;
  uint64_t inc_ = 0;
};

}  // namespace candela
