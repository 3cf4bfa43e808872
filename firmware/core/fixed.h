// Q16.16 fixed-point numbers for animation state. Every operation is integer
// arithmetic, so the same seed yields bit-identical animation on x86 and ARM.
// Floats appear only where values leave the animation for the GPU.
#pragma once

#include <compare>
#include <cstdint>
#include <limits>

namespace candela {

struct Fixed {
  static constexpr int kFracBits = 16;
  static constexpr int32_t kOne = 1 << kFracBits;

  int32_t raw = 0;

  static constexpr Fixed from_raw(int32_t r) { return Fixed{r}; }
  static constexpr Fixed from_int(int32_t i) { return Fixed{i * kOne}; }
  // num/den rounded to nearest: exact for every ratio a config can name.
  static constexpr Fixed from_ratio(int64_t num, int64_t den) {
    int64_t s = num * kOne;
    if (den < 0) s = -s, den = -den;
    return Fixed{static_cast<int32_t>(s >= 0 ? (s + den / 2) / den : -((-s + den / 2) / den))};
  }
  // Only for loading configuration (once, at start-up): rounds to nearest.
  // Saturates at +-32768 (NaN gives 0) rather than overflow, which would be
  // undefined; readers of untrusted numbers check the range first
  // (in_range() below, ParamReader::fixed) and refuse what does not fit.
  static Fixed from_double(double d) {
    const double s = d * kOne;
    if (!(s == s)) return Fixed{};
    if (s >= 2147483646.5) return Fixed{std::numeric_limits<int32_t>::max()};
    if (s <= -2147483647.5) return Fixed{std::numeric_limits<int32_t>::min()};
    return Fixed{static_cast<int32_t>(s >= 0 ? s + 0.5 : s - 0.5)};
  }
  // Whether from_double(d) holds d (to within rounding).
  static bool in_range(double d) { return d > -32768.0 && d < 32767.99998; }
  constexpr float to_float() const { return static_cast<float>(raw) / kOne; }
  constexpr double to_double() const { return static_cast<double>(raw) / kOne; }
  constexpr int32_t floor_int() const { return raw >> kFracBits; }

  friend constexpr Fixed operator+(Fixed a, Fixed b) { return Fixed{a.raw + b.raw}; }
  friend constexpr Fixed operator-(Fixed a, Fixed b) { return Fixed{a.raw - b.raw}; }
  friend constexpr Fixed operator-(Fixed a) { return Fixed{-a.raw}; }
  friend constexpr Fixed operator*(Fixed a, Fixed b) {
    return Fixed{static_cast<int32_t>((static_cast<int64_t>(a.raw) * b.raw) >> kFracBits)};
  }
  friend constexpr Fixed operator*(Fixed a, int32_t k) { return Fixed{a.raw * k}; }
  friend constexpr Fixed operator/(Fixed a, Fixed b) {
    return Fixed{static_cast<int32_t>((static_cast<int64_t>(a.raw) * kOne) / b.raw)};
  }
  friend constexpr Fixed operator/(Fixed a, int32_t k) { return Fixed{a.raw / k}; }
  constexpr Fixed& operator+=(Fixed b) {
    raw += b.raw;
    return *this;
  }
  constexpr Fixed& operator-=(Fixed b) {
    raw -= b.raw;
    return *this;
  }
  constexpr Fixed& operator*=(Fixed b) { return *this = *this * b; }
  friend constexpr auto operator<=>(Fixed a, Fixed b) = default;
};

constexpr Fixed lerp(Fixed a, Fixed b, Fixed t) { return a + (b - a) * t; }
constexpr Fixed clamp(Fixed v, Fixed lo, Fixed hi) { return v < lo ? lo : (v > hi ? hi : v); }
constexpr Fixed abs(Fixed v) { return v.raw < 0 ? -v : v; }

inline namespace fixed_literals {
// 1.5_fx: compile-time only, so no float reaches animation state at run time.
consteval Fixed operator""_fx(long double d) {
  const long double s = d * Fixed::kOne;
  return Fixed::from_raw(static_cast<int32_t>(s >= 0 ? s + 0.5L : s - 0.5L));
}
consteval Fixed operator""_fx(unsigned long long i) {
  return Fixed::from_int(static_cast<int32_t>(i));
}
}  // namespace fixed_literals

}  // namespace candela
