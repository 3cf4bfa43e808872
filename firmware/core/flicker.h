// A fire's flicker: three smooth random signals at fire-like rates (fast
// flutter, mid flicker, slow swell), fixed-point and seeded, so the same seed
// gives the same values on every machine; it does not repeat for years (a
// 2^32-point hashed lattice). The hearth's firelight and the Perlin fire's
// breathing use it.
#pragma once

#include <cstdint>

#include "core/fixed.h"

namespace candela {

class Flicker {
 public:
  explicit Flicker(uint64_t seed);
  // Light at time t (seconds since start): about 1 on average, 0.55..1.35.
  Fixed at(Fixed t) const;
  // The flutter of a flame's light alone: -1..1 at 30 random values a second,
  // smoothly joined, so most of its power lies between 2 and 15 Hz (a fire's
  // tongues tearing off; at() reaches about 6 Hz).
  Fixed flutter(Fixed t) const;
  // Smoothly joined random values at lattice coordinate x (Q16.16: one
  // random value per whole x), -1..1; each stream is a signal of its own.
  Fixed noise(int64_t x_q16, uint32_t stream) const;

 private:
  Fixed value_noise(int64_t t_q16, int rate_hz_x10, uint32_t stream) const;
  uint32_t key_;
};

}  // namespace candela
