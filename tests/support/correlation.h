// Pearson correlation of two equally long series, for tests that compare
// signals, images or profiles (0 when either does not vary, so a flat series
// fails a "correlates above" assertion instead of giving NaN). Header only:
// any test includes it ("support/correlation.h").
#pragma once

#include <cmath>
#include <cstddef>
#include <vector>

namespace candela::test {

template <typename T>
double correlation(const std::vector<T>& a, const std::vector<T>& b) {
  const size_t n = a.size() < b.size() ? a.size() : b.size();
  if (n == 0) return 0.0;
  double ma = 0, mb = 0;
  for (size_t i = 0; i < n; ++i) ma += a[i], mb += b[i];
  ma /= static_cast<double>(n), mb /= static_cast<double>(n);
  double sab = 0, saa = 0, sbb = 0;
  for (size_t i = 0; i < n; ++i) {
    sab += (a[i] - ma) * (b[i] - mb);
    saa += (a[i] - ma) * (a[i] - ma);
    sbb += (b[i] - mb) * (b[i] - mb);
  }
  return saa > 0 && sbb > 0 ? sab / std::sqrt(saa * sbb) : 0.0;
}

}  // namespace candela::test
