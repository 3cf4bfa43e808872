// Integer-only square root, sine and cosine for Q16.16 animation state, so
// wind and candle motion stay bit-identical across CPUs (libm's sin/cos are
// not guaranteed to round alike on x86 and ARM).
#pragma once

#include <cstdint>

#include "core/fixed.h"

namespace candela {

// floor(sqrt(n)) for any 64-bit n, bit by bit.
constexpr uint64_t isqrt64(uint64_t n) {
  uint64_t root = 0;
  uint64_t bit = uint64_t{1} << 62;
  while (bit > n) bit >>= 2;
  while (bit) {
    if (n >= root + bit) {
      n -= root + bit;
      root = (root >> 1) + bit;
    } else {
      root >>= 1;
    }
    bit >>= 2;
  }
  return root;
}

// sqrt(v) for v >= 0 (negative gives 0).
constexpr Fixed fixed_sqrt(Fixed v) {
  if (v.raw <= 0) return Fixed{};
  return Fixed::from_raw(static_cast<int32_t>(isqrt64(static_cast<uint64_t>(v.raw) << 16)));
}

// |(x, z)|, without overflow for components up to the Q16.16 range.
constexpr Fixed fixed_hypot(Fixed x, Fixed z) {
  const uint64_t s = static_cast<uint64_t>(static_cast<int64_t>(x.raw) * x.raw) +
                     static_cast<uint64_t>(static_cast<int64_t>(z.raw) * z.raw);
  return Fixed::from_raw(static_cast<int32_t>(isqrt64(s)));
}

namespace fixed_math_detail {
constexpr int64_t kOneQ30 = int64_t{1} << 30;
constexpr int64_t kPiQ30 = 3373259426;      // pi * 2^30
constexpr int64_t kHalfPiQ30 = 1686629713;  // pi/2 * 2^30
constexpr int64_t kTwoPiQ30 = 6746518852;   // 2 pi * 2^30
}  // namespace fixed_math_detail

// sin of an angle in radians: Taylor series to x^9 on [-pi/2, pi/2] in Q2.30,
// error below 4e-6 (under one Q16 step).
constexpr Fixed fixed_sin(Fixed radians) {
  using namespace fixed_math_detail;
  int64_t x = static_cast<int64_t>(radians.raw) << 14;  // Q30
  x %= kTwoPiQ30;
  if (x > kPiQ30) x -= kTwoPiQ30;
  if (x < -kPiQ30) x += kTwoPiQ30;
  if (x > kHalfPiQ30) x = kPiQ30 - x;
  if (x < -kHalfPiQ30) x = -kPiQ30 - x;
  const int64_t x2 = (x * x) >> 30;
  int64_t t = kOneQ30 - x2 / 72;
  t = kOneQ30 - ((x2 * t) >> 30) / 42;
  t = kOneQ30 - ((x2 * t) >> 30) / 20;
  t = kOneQ30 - ((x2 * t) >> 30) / 6;
  const int64_t s = (x * t) >> 30;
  return Fixed::from_raw(static_cast<int32_t>((s + (int64_t{1} << 13)) >> 14));
}

constexpr Fixed fixed_cos(Fixed radians) {
  return fixed_sin(radians +
                   Fixed::from_raw(static_cast<int32_t>(fixed_math_detail::kHalfPiQ30 >> 14)));
}

// Whole steps in `seconds` at `steps_per_second`, in 64 bits (the product
// can exceed Q16.16's range for long times).
constexpr int64_t steps_in(Fixed seconds, int32_t steps_per_second) {
  return (static_cast<int64_t>(seconds.raw) * steps_per_second) >> Fixed::kFracBits;
}

// Degrees to radians for configuration values (exact to Q16 rounding).
inline Fixed fixed_radians(double degrees) {
  return Fixed::from_double(degrees * 3.14159265358979323846 / 180.0);
}

}  // namespace candela
