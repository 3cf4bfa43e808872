#include "core/flicker.h"

namespace candela {
namespace {

// A 32-bit integer hash (lowbias32): random values at lattice points.
uint32_t hash32(uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352dU;
  x ^= x >> 15;
  x *= 0x846ca68bU;
  x ^= x >> 16;
  return x;
}

}  // namespace

Flicker::Flicker(uint64_t seed)
    : key_(hash32(static_cast<uint32_t>(seed) ^ hash32(static_cast<uint32_t>(seed >> 32)))) {}

Fixed Flicker::noise(int64_t x_q16, uint32_t stream) const {
  const auto i = static_cast<uint32_t>(x_q16 >> Fixed::kFracBits);
  const int32_t f = static_cast<int32_t>(x_q16 & (Fixed::kOne - 1));
  const auto lattice = [&](uint32_t k) {
    return static_cast<int32_t>(hash32(k ^ key_ ^ (stream * 0x9e3779b9U)) >> 15) - Fixed::kOne;
  };
  const int32_t a = lattice(i), b = lattice(i + 1);
  // Smoothstep weight 3f^2 - 2f^3 in Q16.16.
  const int64_t f2 = static_cast<int64_t>(f) * f >> Fixed::kFracBits;
  const int64_t w = (3 * f2) - (2 * f2 * f >> Fixed::kFracBits);
  return Fixed::from_raw(static_cast<int32_t>(a + ((b - a) * w >> Fixed::kFracBits)));
}

// `rate` lattice points per second (rate_hz_x10 / 10).
Fixed Flicker::value_noise(int64_t t_q16, int rate_hz_x10, uint32_t stream) const {
  return noise(t_q16 * rate_hz_x10 / 10, stream);
}

Fixed Flicker::at(Fixed t) const {
  const int64_t tq = t.raw;
  // Weights 0.16, 0.12, 0.07 of -1..1 signals at 11, 4.3 and 0.7 Hz.
  const int64_t sum = int64_t{value_noise(tq, 110, 1).raw} * 16 +
                      int64_t{value_noise(tq, 43, 2).raw} * 12 +
                      int64_t{value_noise(tq, 7, 3).raw} * 7;
  return Fixed::from_raw(Fixed::kOne + static_cast<int32_t>(sum / 100));
}

Fixed Flicker::flutter(Fixed t) const { return value_noise(t.raw, 300, 4); }

}  // namespace candela
