// flame_features.py in C++: the same steps in the same order, in double precision
// (numpy works in float32 there; the difference is far below what the features
// resolve). Gray values are v = u8 / 255, so the thresholds become integer ones.
#include <fftw3.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numeric>
#include <stdexcept>

#include "core/error.h"
#include "measure/measure.h"
#include "measure/numeric.h"

namespace candela::measure {

namespace {

// v > 0.25 <=> u >= 64; v >= 0.95 <=> u >= 243; 0.15 < v < 0.6 <=> 39 <= u <= 152
// (153 / 255 is 0.6 exactly, in float32 as in double).
constexpr uint8_t kFlameU8 = 64;
constexpr uint8_t kCoreU8 = 243;
constexpr uint8_t kBandLoU8 = 39;
constexpr uint8_t kBandHiU8 = 152;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace

const std::vector<std::string>& feature_names() {
  static const std::vector<std::string> names = {"tau_s", "sharp",   "spat_slope", "iso",
                                                 "parts", "area_cv", "core"};
  return names;
}

double feature(const Features& f, const std::string& name) {
  if (name == "tau_s") return f.tau_s;
  if (name == "sharp") return f.sharp;
  if (name == "spat_slope") return f.spat_slope;
  if (name == "iso") return f.iso;
  if (name == "parts") return f.parts;
  if (name == "area_cv") return f.area_cv;
  if (name == "core") return f.core;
  throw std::invalid_argument("unknown feature '" + name + "'");
}

std::vector<double> heights(const Frames& v) {
  std::vector<double> hs(v.count);
  for (int t = 0; t < v.count; ++t) {
    const uint8_t* f = v.frame(t);
    int lo = -1, hi = -1;
    for (int y = 0; y < v.height; ++y) {
      const uint8_t* row = f + static_cast<size_t>(y) * v.width;
      if (*std::max_element(row, row + v.width) >= kFlameU8) {
        if (lo < 0) lo = y;
        hi = y;
      }
    }
    hs[t] = lo < 0 ? 0.0 : hi - lo + 1;
  }
  return hs;
}

Frames normalise(const Frames& raw, const std::string& where, const LoadLimits& limits) {
  const double h = num::median(heights(raw));
  if (h < 4)
    throw ConfigError(where, "",
                      "no flame found (median flame height " + std::to_string(h) +
                          " px: no rows with pixels above 0.25 gray in most frames)");
  const double s = kNormHeight / h;
  // Python's round(): half to even, which nearbyint does in the default mode.
  const double w2 = std::max(8.0, std::nearbyint(raw.width * s));
  const double h2 = std::max(8.0, std::nearbyint(raw.height * s));
  if (w2 > limits.max_side || h2 > limits.max_side ||
      w2 * h2 * raw.count > static_cast<double>(limits.max_bytes))
    throw ConfigError(where, "",
                      "the flame is too small for its frame: scaling its median height (" +
                          std::to_string(h) + " px) to 128 px would make " +
                          std::to_string(static_cast<long long>(w2)) + "x" +
                          std::to_string(static_cast<long long>(h2)) +
                          " frames, beyond the size limit (crop the frames to the flame)");
  return resize_bilinear_pil(raw, static_cast<int>(w2), static_cast<int>(h2));
}

double tau(const Frames& v, double fps) {
  const int n = v.count, hh = v.height / 2, ww = v.width / 2;
  const size_t px = static_cast<size_t>(hh) * ww;
  // Frames averaged 2x2, then the pixels whose mean over time is > 0.1.
  std::vector<double> avg(px * n);
  std::vector<double> mean(px, 0.0);
  for (int t = 0; t < n; ++t) {
    const uint8_t* f = v.frame(t);
    double* a = &avg[px * t];
    for (int y = 0; y < hh; ++y)
      for (int x = 0; x < ww; ++x) {
        const uint8_t* p = f + static_cast<size_t>(2 * y) * v.width + 2 * x;
        const double s = (p[0] + p[1] + p[v.width] + p[v.width + 1]) / 255.0;
        a[y * ww + x] = s / 4.0;
        mean[y * ww + x] += s / 4.0;
      }
  }
  for (double& m : mean) m /= n;
  // Kept pixels: in the region and not constant (variance > 1e-5), mean removed.
  std::vector<size_t> keep;
  std::vector<double> pmean;
  for (size_t p = 0; p < px; ++p) {
    if (!(mean[p] > 0.1)) continue;
    double m = 0;
    for (int t = 0; t < n; ++t) m += avg[px * t + p];
    m /= n;
    double var = 0;
    for (int t = 0; t < n; ++t) {
      const double d = avg[px * t + p] - m;
      var += d * d;
    }
    if (var / n > 1e-5) {
      keep.push_back(p);
      pmean.push_back(m);
    }
  }
  if (keep.empty()) return kNaN;
  const size_t k = keep.size();
  std::vector<double> x(k * n);
  for (int t = 0; t < n; ++t)
    for (size_t i = 0; i < k; ++i) x[k * t + i] = avg[px * t + keep[i]] - pmean[i];
  double denom = 0;
  for (double e : x) denom += e * e;
  const int last = static_cast<int>(std::min<double>(n / 2, std::floor(fps * 3)));
  double prev = 1.0;
  for (int lag = 1; lag < last; ++lag) {
    double s = 0;
    const double* a = &x[k * lag];
    const double* b = x.data();
    const size_t m = k * static_cast<size_t>(n - lag);
    for (size_t i = 0; i < m; ++i) s += a[i] * b[i];
    const double r = s / denom * n / (n - lag);
    if (r < 0.5) {
      const double frac = prev != r ? (prev - 0.5) / (prev - r) : 0.0;
      return (lag - 1 + frac) / fps;
    }
    prev = r;
  }
  return last / fps;
}

double sharpness(const Frames& v) {
  // numpy.gradient: central differences inside, one-sided at the edges.
  const int w = v.width, h = v.height;
  double sum = 0;
  size_t count = 0;
  for (int t = 0; t < v.count; ++t) {
    const uint8_t* f = v.frame(t);
    auto at = [&](int x, int y) { return static_cast<double>(f[static_cast<size_t>(y) * w + x]); };
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const uint8_t u = f[static_cast<size_t>(y) * w + x];
        if (u < kBandLoU8 || u > kBandHiU8) continue;
        double gx, gy;
        if (w < 2)
          gx = 0;
        else if (x == 0)
          gx = at(1, y) - at(0, y);
        else if (x == w - 1)
          gx = at(w - 1, y) - at(w - 2, y);
        else
          gx = (at(x + 1, y) - at(x - 1, y)) / 2.0;
        if (h < 2)
          gy = 0;
        else if (y == 0)
          gy = at(x, 1) - at(x, 0);
        else if (y == h - 1)
          gy = at(x, h - 1) - at(x, h - 2);
        else
          gy = (at(x, y + 1) - at(x, y - 1)) / 2.0;
        sum += std::sqrt(gx * gx + gy * gy) / 255.0;
        ++count;
      }
  }
  return count ? sum / count : kNaN;
}

Box flame_box(const Frames& v) {
  const size_t px = v.frame_size();
  std::vector<uint8_t> any(px, 0);
  for (int t = 0; t < v.count; ++t) {
    const uint8_t* f = v.frame(t);
    for (size_t p = 0; p < px; ++p) any[p] |= f[p] >= kFlameU8;
  }
  int y0 = v.height, y1 = -1, x0 = v.width, x1 = -1;
  for (int y = 0; y < v.height; ++y)
    for (int x = 0; x < v.width; ++x)
      if (any[static_cast<size_t>(y) * v.width + x]) {
        y0 = std::min(y0, y);
        y1 = std::max(y1, y);
        x0 = std::min(x0, x);
        x1 = std::max(x1, x);
      }
  if (y1 < 0) return {0, v.height, 0, v.width};  // normalise() guarantees a flame
  constexpr int pad = 4;
  return {std::max(0, y0 - pad), std::min(v.height, y1 + 1 + pad), std::max(0, x0 - pad),
          std::min(v.width, x1 + 1 + pad)};
}

double spatial_slope(const Frames& v, const Box& box) {
  const int hh = box.y1 - box.y0, ww = box.x1 - box.x0;
  const size_t px = static_cast<size_t>(hh) * ww;
  const std::vector<double> wy = num::hanning(hh), wx = num::hanning(ww);
  struct FftwFree {
    void operator()(void* p) const { fftw_free(p); }
  };
  std::unique_ptr<fftw_complex, FftwFree> in(fftw_alloc_complex(px)), out(fftw_alloc_complex(px));
  fftw_plan plan = fftw_plan_dft_2d(hh, ww, in.get(), out.get(), FFTW_FORWARD, FFTW_ESTIMATE);
  std::vector<double> acc(px, 0.0);
  const int step = std::max(1, v.count / 60);
  for (int t = 0; t < v.count; t += step) {
    const uint8_t* f = v.frame(t);
    double mean = 0;
    for (int y = 0; y < hh; ++y)
      for (int x = 0; x < ww; ++x)
        mean += f[static_cast<size_t>(y + box.y0) * v.width + x + box.x0] / 255.0;
    mean /= static_cast<double>(px);
    for (int y = 0; y < hh; ++y)
      for (int x = 0; x < ww; ++x) {
        const double c = f[static_cast<size_t>(y + box.y0) * v.width + x + box.x0] / 255.0;
        in.get()[static_cast<size_t>(y) * ww + x][0] = (c - mean) * (wy[y] * wx[x]);
        in.get()[static_cast<size_t>(y) * ww + x][1] = 0.0;
      }
    fftw_execute(plan);
    for (size_t p = 0; p < px; ++p) {
      const double re = out.get()[p][0], im = out.get()[p][1];
      acc[p] += re * re + im * im;
    }
  }
  fftw_destroy_plan(plan);
  // Radial bins, geometric edges from 2/128 to 0.25 cycles per pixel.
  const std::vector<double> fy = num::fftfreq(hh), fx = num::fftfreq(ww);
  const std::vector<double> edges = num::geomspace(2.0 / kNormHeight, 0.25, 16);
  std::vector<double> sum(edges.size() - 1, 0.0);
  std::vector<size_t> cnt(edges.size() - 1, 0);
  for (int y = 0; y < hh; ++y)
    for (int x = 0; x < ww; ++x) {
      const double r = std::sqrt(fx[x] * fx[x] + fy[y] * fy[y]);
      if (r < edges.front() || !(r < edges.back())) continue;
      // The bin with edges[i] <= r < edges[i + 1].
      const size_t i = std::upper_bound(edges.begin(), edges.end(), r) - edges.begin() - 1;
      sum[i] += acc[static_cast<size_t>(y) * ww + x];
      ++cnt[i];
    }
  std::vector<double> lf, lp;
  for (size_t i = 0; i + 1 < edges.size(); ++i)
    if (cnt[i]) {
      lf.push_back(std::log10(std::sqrt(edges[i] * edges[i + 1])));
      lp.push_back(std::log10(sum[i] / cnt[i] + 1e-30));
    }
  return num::linear_fit_slope(lf, lp);
}

ShapeStats shape_stats(const Frames& v) {
  const int w = v.width, h = v.height;
  const size_t px = v.frame_size();
  std::vector<double> isos, parts, areas;
  std::vector<int> label(px);
  std::vector<int> stack;
  std::vector<double> sizes;
  for (int t = 0; t < v.count; ++t) {
    const uint8_t* f = v.frame(t);
    auto in = [&](int x, int y) {
      return x >= 0 && y >= 0 && x < w && y < h && f[static_cast<size_t>(y) * w + x] >= kFlameU8;
    };
    size_t a = 0, perim = 0;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        if (!in(x, y)) continue;
        ++a;
        // binary_erosion with the cross and border 0: a flame pixel stays unless a
        // 4-neighbour is background or outside; the ones that go are the perimeter.
        if (!in(x - 1, y) || !in(x + 1, y) || !in(x, y - 1) || !in(x, y + 1)) ++perim;
      }
    if (a < 10) continue;
    isos.push_back(static_cast<double>(perim) * perim / (4 * M_PI * a));
    // Connected components, 4-connectivity (ndimage.label's default).
    std::fill(label.begin(), label.end(), 0);
    sizes.clear();
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const size_t p0 = static_cast<size_t>(y) * w + x;
        if (label[p0] || !in(x, y)) continue;
        const int id = static_cast<int>(sizes.size()) + 1;
        double size = 0;
        label[p0] = id;
        stack.assign(1, static_cast<int>(p0));
        while (!stack.empty()) {
          const int p = stack.back();
          stack.pop_back();
          ++size;
          const int px_ = p % w, py = p / w;
          const int nx[4] = {px_ - 1, px_ + 1, px_, px_};
          const int ny[4] = {py, py, py - 1, py + 1};
          for (int j = 0; j < 4; ++j)
            if (in(nx[j], ny[j])) {
              const size_t q = static_cast<size_t>(ny[j]) * w + nx[j];
              if (!label[q]) {
                label[q] = id;
                stack.push_back(static_cast<int>(q));
              }
            }
        }
        sizes.push_back(size);
      }
    const double big = *std::max_element(sizes.begin(), sizes.end());
    int n = 0;
    for (double s : sizes) n += s >= 0.005 * big;
    parts.push_back(n);
    areas.push_back(static_cast<double>(a));
  }
  if (areas.empty()) return {kNaN, kNaN, kNaN};
  return {num::mean(isos), num::mean(parts), num::pstd(areas) / num::mean(areas)};
}

double core(const Frames& v) {
  size_t flame = 0, white = 0;
  for (uint8_t u : v.pixels) {
    flame += u >= kFlameU8;
    white += u >= kCoreU8;
  }
  return static_cast<double>(white) / static_cast<double>(std::max<size_t>(1, flame));
}

Features features(const Frames& raw, double fps, const std::string& where,
                  const LoadLimits& limits) {
  const Frames v = normalise(raw, where, limits);
  Features f;
  f.frames = v.count;
  f.fps = fps;
  const Box box = flame_box(v);
  const ShapeStats s = shape_stats(v);
  f.tau_s = tau(v, fps);
  f.sharp = sharpness(v);
  f.spat_slope = spatial_slope(v, box);
  f.iso = s.iso;
  f.parts = s.parts;
  f.area_cv = s.area_cv;
  f.core = core(v);
  return f;
}

}  // namespace candela::measure
