// realism.py in C++: the I/H/X/W series, their spectra and slopes, log-spectral
// distances, and the longest repeated stretch.
#include <fftw3.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <memory>

#include "measure/measure.h"
#include "measure/numeric.h"

namespace candela::measure {

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
}

const std::vector<double>& series_by_index(const Series& s, int i) {
  switch (i) {
    case 0:
      return s.I;
    case 1:
      return s.H;
    case 2:
      return s.X;
    default:
      return s.W;
  }
}

Series series(const Frames& v) {
  Series s;
  s.H = heights(v);
  const int w = v.width, h = v.height;
  std::vector<double> col(w);
  for (int t = 0; t < v.count; ++t) {
    const uint8_t* f = v.frame(t);
    std::fill(col.begin(), col.end(), 0.0);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) col[x] += f[static_cast<size_t>(y) * w + x];
    double total = 0, sx = 0, sxx = 0;
    for (int x = 0; x < w; ++x) {
      const double c = col[x] / 255.0;
      total += c;
      sx += c * x;
      sxx += c * x * x;
    }
    s.I.push_back(total / (static_cast<double>(w) * h));
    const double m = total + 1e-9;
    const double X = sx / m;
    s.X.push_back(X);
    s.W.push_back(std::sqrt(std::max(sxx / m - X * X, 0.0)));
  }
  return s;
}

Psd psd(const std::vector<double>& x0, double fps) {
  const int n = static_cast<int>(x0.size());
  const double m = num::mean(x0);
  std::vector<double> x(n);
  for (int i = 0; i < n; ++i) x[i] = x0[i] - m;
  const int seg = static_cast<int>(std::min<double>(n, std::max(16.0, 2 * fps)));
  const int step = std::max(1, seg / 2);
  const std::vector<double> win = num::hanning(seg);
  const int bins = seg / 2 + 1;
  Psd out;
  out.f = num::rfftfreq(seg, 1.0 / fps);
  out.p.assign(bins, 0.0);
  if (seg < 1) return out;
  struct FftwFree {
    void operator()(void* p) const { fftw_free(p); }
  };
  std::unique_ptr<double, FftwFree> in(fftw_alloc_real(seg));
  std::unique_ptr<fftw_complex, FftwFree> spec(fftw_alloc_complex(bins));
  fftw_plan plan = fftw_plan_dft_r2c_1d(seg, in.get(), spec.get(), FFTW_ESTIMATE);
  int k = 0;
  for (int s = 0; s + seg <= n; s += step) {
    for (int i = 0; i < seg; ++i) in.get()[i] = x[s + i] * win[i];
    fftw_execute(plan);
    for (int b = 0; b < bins; ++b) {
      const double re = spec.get()[b][0], im = spec.get()[b][1];
      out.p[b] += re * re + im * im;
    }
    ++k;
  }
  fftw_destroy_plan(plan);
  for (double& p : out.p) p /= std::max(k, 1);
  return out;
}

double spectral_slope(const std::vector<double>& x, double fps) {
  const Psd p = psd(x, fps);
  const double top = std::min(fps / 2.0, 12.0);
  std::vector<double> lf, lp;
  for (size_t i = 0; i < p.f.size(); ++i)
    if (p.f[i] >= 0.5 && p.f[i] <= top && p.p[i] > 0) {
      lf.push_back(std::log10(p.f[i]));
      lp.push_back(std::log10(p.p[i]));
    }
  if (lf.size() < 3) return kNaN;
  return num::linear_fit_slope(lf, lp);
}

Stats stats(const Series& s, double fps) {
  Stats out;
  out.frames = static_cast<int>(s.I.size());
  out.fps = fps;
  for (int i = 0; i < 4; ++i) {
    const auto& x = series_by_index(s, i);
    out.s[i] = {num::mean(x), num::pstd(x), spectral_slope(x, fps)};
  }
  return out;
}

double lsd(const std::vector<double>& xa, double fa, const std::vector<double>& xb, double fb) {
  const Psd a = psd(xa, fa), b = psd(xb, fb);
  const double hi = std::min(fa, fb) / 2.0;
  const std::vector<double> grid = num::linspace(0.5, std::min(hi, 12.0), 40);
  std::vector<double> pa(grid.size()), pb(grid.size());
  double sa = 0, sb = 0;
  for (size_t i = 0; i < grid.size(); ++i) {
    pa[i] = num::interp(grid[i], a.f, a.p);
    pb[i] = num::interp(grid[i], b.f, b.p);
    sa += pa[i];
    sb += pb[i];
  }
  double acc = 0;
  for (size_t i = 0; i < grid.size(); ++i) {
    const double ra = pa[i] / (sa + 1e-30), rb = pb[i] / (sb + 1e-30);
    const double d = 10 * std::log10((ra + 1e-30) / (rb + 1e-30));
    acc += d * d;
  }
  return std::sqrt(acc / static_cast<double>(grid.size()));
}

Comparison compare(const Series& a, double fa, const Series& b, double fb) {
  Comparison c;
  for (int i = 0; i < 4; ++i) {
    const auto& xa = series_by_index(a, i);
    const auto& xb = series_by_index(b, i);
    const double sda = num::pstd(xa), sdb = num::pstd(xb);
    c.s[i] = {lsd(xa, fa, xb, fb), sda > 0 ? sdb / sda : kNaN};
  }
  return c;
}

double longest_repeat_s(const Frames& v, double fps, double frac) {
  const int n = v.count;
  if (n < 3) return 0.0;
  // Every 4th pixel in both directions, as v[:, ::4, ::4].
  const int sw = (v.width + 3) / 4, sh = (v.height + 3) / 4;
  const size_t p = static_cast<size_t>(sw) * sh;
  std::vector<uint8_t> small(p * n);
  for (int t = 0; t < n; ++t)
    for (int y = 0; y < sh; ++y)
      for (int x = 0; x < sw; ++x)
        small[p * t + static_cast<size_t>(y) * sw + x] =
            v.frame(t)[static_cast<size_t>(4 * y) * v.width + 4 * x];
  auto mad = [&](int a, int b) {  // mean |difference| on the 0..1 scale
    const uint8_t* pa = &small[p * a];
    const uint8_t* pb = &small[p * b];
    unsigned long s = 0;
    for (size_t i = 0; i < p; ++i) s += static_cast<unsigned>(std::abs(pa[i] - pb[i]));
    return static_cast<double>(s) / 255.0 / static_cast<double>(p);
  };
  std::vector<double> steps(n - 1);
  for (int t = 0; t + 1 < n; ++t) steps[t] = mad(t + 1, t);
  const double tol = frac * num::median(steps);
  int best = 0;
  for (int lag = 2; lag < n; ++lag) {
    int run = 0;
    for (int t = 0; t + lag < n; ++t) {
      run = mad(t + lag, t) < tol ? run + 1 : 0;
      best = std::max(best, run);
    }
  }
  return best / fps;
}

}  // namespace candela::measure
