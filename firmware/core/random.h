// Seeded, platform-independent random numbers (PCG32, O'Neill 2014). The
// standard library's distributions differ between implementations, so every
// draw used by animation goes through here.
#pragma once

#include <cstdint>

#include "core/fixed.h"

namespace candela {

// SplitMix64 (Steele, Lea and Flood 2014). The golden-ratio increment of
// its state, and its finaliser: a well-spread 64-bit hash of z.
inline constexpr uint64_t kSplitMix64Gamma = 0x9E3779B97F4A7C15ULL;
constexpr uint64_t splitmix64_mix(uint64_t z) {
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}
// One seed spread into independent seeds, one per index (the SplitMix64
// sequence from `seed`, its index+1'th output): a scene's elements, a story's
// segments, a synthesiser's parts, a group's candles.
constexpr uint64_t split_seed(uint64_t seed, uint64_t index) {
  return splitmix64_mix(seed + kSplitMix64Gamma * (index + 1));
}

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
