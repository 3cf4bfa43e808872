// The few numpy conventions the yardsticks depend on, written the way numpy
// computes them (so bin edges and band limits fall where the scripts' do).
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace candela::measure::num {

inline double mean(const std::vector<double>& x) {
  if (x.empty()) return std::numeric_limits<double>::quiet_NaN();
  double s = 0;
  for (double v : x) s += v;
  return s / static_cast<double>(x.size());
}

// Population standard deviation (np.std, ddof 0).
inline double pstd(const std::vector<double>& x) {
  const double m = mean(x);
  double s = 0;
  for (double v : x) s += (v - m) * (v - m);
  return std::sqrt(s / static_cast<double>(x.size()));
}

// np.median: the middle value, or the mean of the two middle ones.
inline double median(std::vector<double> x) {
  if (x.empty()) return std::numeric_limits<double>::quiet_NaN();
  const size_t n = x.size(), h = n / 2;
  std::nth_element(x.begin(), x.begin() + h, x.end());
  const double hi = x[h];
  if (n % 2) return hi;
  const double lo = *std::max_element(x.begin(), x.begin() + h);
  return (lo + hi) / 2.0;
}

// np.hanning(M): 0.5 + 0.5 cos(pi n / (M - 1)), n = 1-M, 3-M, ..., M-1.
inline std::vector<double> hanning(int m) {
  if (m < 1) return {};
  if (m == 1) return {1.0};
  std::vector<double> w(m);
  for (int i = 0; i < m; ++i) {
    const double n = 1 - m + 2 * i;
    w[i] = 0.5 + 0.5 * std::cos(M_PI * n / (m - 1));
  }
  return w;
}

// np.fft.fftfreq(n, d): [0, 1, ..., (n-1)/2, -(n/2), ..., -1] * (1 / (n d)).
inline std::vector<double> fftfreq(int n, double d = 1.0) {
  const double val = 1.0 / (n * d);
  std::vector<double> f(n);
  const int half = (n - 1) / 2 + 1;
  for (int i = 0; i < half; ++i) f[i] = i * val;
  for (int i = half; i < n; ++i) f[i] = (i - n) * val;
  return f;
}

// np.fft.rfftfreq(n, d): [0, 1, ..., n/2] * (1 / (n d)).
inline std::vector<double> rfftfreq(int n, double d = 1.0) {
  const double val = 1.0 / (n * d);
  std::vector<double> f(n / 2 + 1);
  for (int i = 0; i <= n / 2; ++i) f[i] = i * val;
  return f;
}

// np.linspace(a, b, n) (endpoint included): i * step + a, the last set to b.
inline std::vector<double> linspace(double a, double b, int n) {
  std::vector<double> y(n);
  if (n == 1) return {a};
  const double step = (b - a) / (n - 1);
  for (int i = 0; i < n; ++i) y[i] = i * step + a;
  y[n - 1] = b;
  return y;
}

// np.geomspace(a, b, n): 10 ** linspace(log10 a, log10 b), the ends set exactly.
inline std::vector<double> geomspace(double a, double b, int n) {
  std::vector<double> y = linspace(std::log10(a), std::log10(b), n);
  for (double& v : y) v = std::pow(10.0, v);
  y.front() = a;
  y.back() = b;
  return y;
}

// Slope of the least-squares line (np.polyfit(x, y, 1)[0]); NaN if undefined.
inline double linear_fit_slope(const std::vector<double>& x, const std::vector<double>& y) {
  if (x.size() < 2) return std::numeric_limits<double>::quiet_NaN();
  const double mx = mean(x), my = mean(y);
  double sxy = 0, sxx = 0;
  for (size_t i = 0; i < x.size(); ++i) {
    sxy += (x[i] - mx) * (y[i] - my);
    sxx += (x[i] - mx) * (x[i] - mx);
  }
  return sxx > 0 ? sxy / sxx : std::numeric_limits<double>::quiet_NaN();
}

// np.interp(x, xp, fp) for increasing xp: linear, clamped to the end values.
inline double interp(double x, const std::vector<double>& xp, const std::vector<double>& fp) {
  if (x <= xp.front()) return fp.front();
  if (x >= xp.back()) return fp.back();
  const size_t j = std::upper_bound(xp.begin(), xp.end(), x) - xp.begin() - 1;
  if (xp[j] == x) return fp[j];
  const double slope = (fp[j + 1] - fp[j]) / (xp[j + 1] - xp[j]);
  return slope * (x - xp[j]) + fp[j];
}

}  // namespace candela::measure::num
