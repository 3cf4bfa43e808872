#include "noise/noise_synth.h"

#include <fftw3.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "core/random.h"

namespace candela::noise {
namespace {

// FFTW's arrays, freed on every path.
template <typename T>
struct FftwArray {
  explicit FftwArray(size_t n) : p(static_cast<T*>(fftw_malloc(sizeof(T) * n))) {
    if (!p) throw std::bad_alloc();
  }
  ~FftwArray() { fftw_free(p); }
  FftwArray(const FftwArray&) = delete;
  FftwArray& operator=(const FftwArray&) = delete;
  T* p;
};

}  // namespace

std::vector<double> synthesize(double beta, uint32_t length, uint64_t seed) {
  if (length < 4 || length % 2) throw std::invalid_argument("noise length must be even and >= 4");
  const size_t n = length;
  FftwArray<fftw_complex> spectrum(n / 2 + 1);
  FftwArray<double> out(n);
  Pcg32 rng(seed);
  // k = 0 (the mean) and k = N/2 (Nyquist, which has no phase of its own) stay
  // zero; FFTW's c2r supplies F(N - k) = conj F(k) for the other half.
  spectrum.p[0][0] = spectrum.p[0][1] = 0;
  spectrum.p[n / 2][0] = spectrum.p[n / 2][1] = 0;
  for (size_t k = 1; k < n / 2; ++k) {
    const double amplitude = 1.0 / std::pow(static_cast<double>(k), beta / 2);
    const double w = 2 * std::numbers::pi * rng.unit_double();
    spectrum.p[k][0] = amplitude * std::cos(w);
    spectrum.p[k][1] = amplitude * std::sin(w);
  }
  fftw_plan plan = fftw_plan_dft_c2r_1d(static_cast<int>(n), spectrum.p, out.p,
                                        FFTW_ESTIMATE | FFTW_DESTROY_INPUT);
  if (!plan) throw std::runtime_error("FFTW could not plan the inverse transform");
  fftw_execute(plan);
  fftw_destroy_plan(plan);
  return std::vector<double>(out.p, out.p + n);
}

std::vector<uint16_t> quantize(std::span<const double> x, bool gust) {
  const auto [lo_it, hi_it] = std::minmax_element(x.begin(), x.end());
  const double lo = *lo_it, hi = *hi_it;
  const double scale = hi > lo ? 65535.0 / (hi - lo) : 0.0;
  const size_t shift = gust ? static_cast<size_t>(lo_it - x.begin()) : 0;
  std::vector<uint16_t> q(x.size());
  for (size_t i = 0; i < x.size(); ++i) {
    const double v = (x[(i + shift) % x.size()] - lo) * scale;
    q[i] = static_cast<uint16_t>(std::clamp(std::lround(v), 0L, 65535L));
  }
  return q;
}

NoiseTable make_table(double beta, uint32_t length, uint64_t seed, bool gust) {
  const auto q = quantize(synthesize(beta, length, seed), gust);
  NoiseTableInfo info;
  info.length = length;
  info.beta_milli = static_cast<int32_t>(std::lround(beta * 1000));
  info.gust = gust;
  info.seed = seed;
  return NoiseTable::parse(NoiseTable::serialize(info, q), "<generated>");
}

SpectrumFit fit_spectral_slope(std::span<const double> x) {
  const size_t n = x.size();
  if (n < 16) throw std::invalid_argument("need at least 16 samples to fit a spectrum");
  FftwArray<double> in(n);
  FftwArray<fftw_complex> spec(n / 2 + 1);
  double mean = 0;
  for (double v : x) mean += v;
  mean /= static_cast<double>(n);
  for (size_t i = 0; i < n; ++i) in.p[i] = x[i] - mean;
  fftw_plan plan = fftw_plan_dft_r2c_1d(static_cast<int>(n), in.p, spec.p, FFTW_ESTIMATE);
  if (!plan) throw std::runtime_error("FFTW could not plan the forward transform");
  fftw_execute(plan);
  fftw_destroy_plan(plan);
  // Log-spaced bins (8 per decade) of mean log power; the table is periodic,
  // so the periodogram needs no window.
  const double per_decade = 8;
  std::vector<double> bx, by;
  double bin_start = 0, sum_lk = 0, sum_lp = 0;
  int count = 0;
  auto flush = [&] {
    if (count) {
      bx.push_back(sum_lk / count);
      by.push_back(sum_lp / count);
    }
    sum_lk = sum_lp = 0;
    count = 0;
  };
  for (size_t k = 1; k < n / 2; ++k) {
    const double lk = std::log10(static_cast<double>(k));
    const double p = spec.p[k][0] * spec.p[k][0] + spec.p[k][1] * spec.p[k][1];
    if (lk >= bin_start + 1 / per_decade) {
      flush();
      bin_start = std::floor(lk * per_decade) / per_decade;
    }
    sum_lk += lk;
    sum_lp += std::log10(std::max(p, 1e-300));
    ++count;
  }
  flush();
  const double m = static_cast<double>(bx.size());
  double sx = 0, sy = 0, sxx = 0, sxy = 0, syy = 0;
  for (size_t i = 0; i < bx.size(); ++i) {
    sx += bx[i];
    sy += by[i];
    sxx += bx[i] * bx[i];
    sxy += bx[i] * by[i];
    syy += by[i] * by[i];
  }
  SpectrumFit f;
  const double den = m * sxx - sx * sx;
  f.slope = (m * sxy - sx * sy) / den;
  f.intercept = (sy - f.slope * sx) / m;
  const double ss_tot = syy - sy * sy / m;
  double ss_res = 0;
  for (size_t i = 0; i < bx.size(); ++i) {
    const double e = by[i] - (f.intercept + f.slope * bx[i]);
    ss_res += e * e;
  }
  f.r2 = ss_tot > 0 ? 1 - ss_res / ss_tot : 1;
  return f;
}

TableStats table_stats(std::span<const double> v) {
  TableStats s;
  if (v.empty()) return s;
  const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
  s.min = *lo;
  s.max = *hi;
  s.argmin = static_cast<uint32_t>(lo - v.begin());
  for (double x : v) s.mean += x;
  s.mean /= static_cast<double>(v.size());
  for (double x : v) s.stddev += (x - s.mean) * (x - s.mean);
  s.stddev = std::sqrt(s.stddev / static_cast<double>(v.size()));
  for (size_t i = 0; i + 1 < v.size(); ++i) s.mean_step += std::abs(v[i + 1] - v[i]);
  s.mean_step /= static_cast<double>(v.size() > 1 ? v.size() - 1 : 1);
  s.wrap_step = std::abs(v.front() - v.back());
  return s;
}

std::vector<double> to_unit(const NoiseTable& t) {
  std::vector<double> v(t.length());
  for (uint32_t i = 0; i < t.length(); ++i) v[i] = t.samples()[i] / 65536.0;
  return v;
}

}  // namespace candela::noise
