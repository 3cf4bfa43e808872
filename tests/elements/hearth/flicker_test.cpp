// The fire's flicker (core/flicker.h): the same seed gives the same light,
// it stays in its range around 1, and it changes at fire-like rates.
#include "core/flicker.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace candela {
namespace {

std::vector<double> series(uint64_t seed, int steps) {
  Flicker f(seed);
  std::vector<double> v;
  for (int i = 0; i < steps; ++i) v.push_back(f.at(Fixed::from_ratio(i, 60)).to_double());
  return v;
}

TEST(Flicker, SameSeedSameValuesBitForBitOtherSeedOther) {
  Flicker a(5), b(5), c(6);
  int differ = 0;
  for (int i = 0; i < 600; ++i) {
    const Fixed t = Fixed::from_ratio(i, 60);
    EXPECT_EQ(a.at(t).raw, b.at(t).raw);
    differ += a.at(t).raw != c.at(t).raw;
  }
  EXPECT_GT(differ, 550);
}

TEST(Flicker, StaysNearOneWithinItsRange) {
  const auto v = series(11, 60 * 120);
  double sum = 0, lo = 9, hi = -9;
  for (double x : v) sum += x, lo = std::min(lo, x), hi = std::max(hi, x);
  EXPECT_NEAR(sum / v.size(), 1.0, 0.05);
  EXPECT_GE(lo, 0.64);
  EXPECT_LE(hi, 1.36);
  EXPECT_GT(hi - lo, 0.3);  // it really flickers
}

TEST(Flicker, ChangesFromFrameToFrameButIsNotNoise) {
  // A fire's light flickers visibly within a tenth of a second, yet each
  // frame follows on from the last (no white-noise jumps).
  const auto v = series(3, 60 * 60);
  double step = 0, tenth = 0;
  for (size_t i = 6; i < v.size(); ++i) {
    step += std::abs(v[i] - v[i - 1]);
    tenth += std::abs(v[i] - v[i - 6]);
  }
  step /= static_cast<double>(v.size() - 6);
  tenth /= static_cast<double>(v.size() - 6);
  EXPECT_GT(tenth, 0.04);
  EXPECT_GT(tenth, 3 * step);
}

}  // namespace
}  // namespace candela
