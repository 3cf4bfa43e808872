#include "lattice_noise.h"

#include <cmath>

namespace candela::fluid {

uint64_t mix64(uint64_t z) {
  z += 0x9e3779b97f4a7c15ull;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

double lattice_hash(uint64_t seed, int64_t i, int64_t j, int64_t k) {
  const uint64_t z = mix64(seed ^ mix64(static_cast<uint64_t>(i) * 0x8da6b343ull ^
                                        static_cast<uint64_t>(j) * 0xd8163841ull ^
                                        static_cast<uint64_t>(k) * 0xcb1ab31full));
  return static_cast<double>(z >> 11) * (1.0 / 9007199254740992.0);
}

double value_noise(uint64_t seed, double x, double y, double t) {
  const double fx = std::floor(x), fy = std::floor(y), ft = std::floor(t);
  const auto ix = static_cast<int64_t>(fx), iy = static_cast<int64_t>(fy),
             it = static_cast<int64_t>(ft);
  auto s = [](double a) { return a * a * (3.0 - 2.0 * a); };
  const double ax = s(x - fx), ay = s(y - fy), at = s(t - ft);
  auto h = [&](int64_t i, int64_t j, int64_t k) { return lattice_hash(seed, i, j, k); };
  double c[2];
  for (int k = 0; k < 2; ++k) {
    const double a = h(ix, iy, it + k) + (h(ix + 1, iy, it + k) - h(ix, iy, it + k)) * ax;
    const double b =
        h(ix, iy + 1, it + k) + (h(ix + 1, iy + 1, it + k) - h(ix, iy + 1, it + k)) * ax;
    c[k] = a + (b - a) * ay;
  }
  return c[0] + (c[1] - c[0]) * at;
}

constexpr double kStdOctave = 0.25;

double pink_flicker(uint64_t seed, double t) {
  // Value noise at frequency f has its power spread below f (density ~1/f
  // there), so equal octaves sum to a density ~1/f: pink. One octave has std
  // ~0.25 about its mean 0.5 (measured: PinkFlicker test); normalised.
  constexpr int kOctaves = 6;
  double sum = 0.0;
  for (int o = 0; o < kOctaves; ++o) {
    const double hz = 0.75 * static_cast<double>(1 << o);
    sum += value_noise(seed + 1000003ull * o, 0.0, 0.0, t * hz) - 0.5;
  }
  return sum / (kStdOctave * std::sqrt(static_cast<double>(kOctaves)));
}

}  // namespace candela::fluid
