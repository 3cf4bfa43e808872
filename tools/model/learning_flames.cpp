#include "learning_flames.h"

#include <algorithm>
#include <cmath>

namespace candela::tools {

CubicSpline::CubicSpline(std::vector<double> t, std::vector<double> v)
    : t_(std::move(t)), v_(std::move(v)) {
  const size_t n = t_.size();
  m_.assign(n, 0.0);
  if (n < 3) return;
  // Tridiagonal system for the second derivatives, natural ends (m = 0).
  std::vector<double> a(n, 0), b(n, 1), c(n, 0), r(n, 0);
  for (size_t i = 1; i + 1 < n; ++i) {
    const double h0 = t_[i] - t_[i - 1], h1 = t_[i + 1] - t_[i];
    a[i] = h0;
    b[i] = 2 * (h0 + h1);
    c[i] = h1;
    r[i] = 6 * ((v_[i + 1] - v_[i]) / h1 - (v_[i] - v_[i - 1]) / h0);
  }
  for (size_t i = 1; i < n; ++i) {
    const double k = a[i] / b[i - 1];
    b[i] -= k * c[i - 1];
    r[i] -= k * r[i - 1];
  }
  m_[n - 1] = r[n - 1] / b[n - 1];
  for (size_t i = n - 1; i-- > 0;) m_[i] = (r[i] - c[i] * m_[i + 1]) / b[i];
}

double CubicSpline::operator()(double t) const {
  const size_t n = t_.size();
  if (n == 1) return v_[0];
  if (t <= t_[0] || t >= t_[n - 1]) {
    // Linear beyond the ends, with the end slope.
    const bool lo = t <= t_[0];
    const size_t i = lo ? 0 : n - 2;
    const double h = t_[i + 1] - t_[i];
    const double slope =
        (v_[i + 1] - v_[i]) / h - h * (lo ? (2 * m_[i] + m_[i + 1]) : -(m_[i] + 2 * m_[i + 1])) / 6;
    return lo ? v_[0] + slope * (t - t_[0]) : v_[n - 1] + slope * (t - t_[n - 1]);
  }
  size_t i = static_cast<size_t>(std::upper_bound(t_.begin(), t_.end(), t) - t_.begin()) - 1;
  i = std::min(i, n - 2);
  const double h = t_[i + 1] - t_[i], A = (t_[i + 1] - t) / h, B = 1 - A;
  return A * v_[i] + B * v_[i + 1] +
         ((A * A * A - A) * m_[i] + (B * B * B - B) * m_[i + 1]) * h * h / 6;
}

namespace {

CubicSpline curve(const std::vector<double>& v) {
  std::vector<double> t(v.size());
  for (size_t i = 0; i < v.size(); ++i)
    t[i] = sample_height(static_cast<int>(i), static_cast<int>(v.size()));
  return CubicSpline(t, v);
}

// Bilinear sample at pixel-centre coordinates; outside the image counts as 0.
template <class Pixel>
float bilinear(const Pixel* img, int w, int h, double x, double y) {
  x -= 0.5;
  y -= 0.5;
  const int x0 = static_cast<int>(std::floor(x)), y0 = static_cast<int>(std::floor(y));
  const double fx = x - x0, fy = y - y0;
  double acc = 0;
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i) {
      const int xi = x0 + i, yj = y0 + j;
      if (xi < 0 || yj < 0 || xi >= w || yj >= h) continue;
      acc += (i ? fx : 1 - fx) * (j ? fy : 1 - fy) * img[static_cast<size_t>(yj) * w + xi];
    }
  return static_cast<float>(acc);
}

}  // namespace

FlameShape measure_shape(const uint8_t* frame, int width, int height, const ShapeOptions& o) {
  FlameShape s;
  const double base = o.base_row;
  // Height: from the row masses (zeroth moments of the rows) above the base.
  std::vector<double> rows(height, 0.0);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) rows[y] += frame[static_cast<size_t>(y) * width + x];
  const double peak = *std::max_element(rows.begin(), rows.end());
  int top = 0;
  while (top < height - 1 && rows[top] < o.tip_fraction * peak) ++top;
  s.height = std::max(4.0, base - top);
  // Per height slice: centre (first moment) and width (second central moment).
  auto slice_moments = [&](int n, std::vector<double>& centre, std::vector<double>& spread) {
    centre.assign(n, width / 2.0);
    spread.assign(n, 2.0);
    std::vector<bool> ok(n, false);
    for (int i = 0; i < n; ++i) {
      const double y1 = base - s.height * i / n, y0 = base - s.height * (i + 1) / n;
      double m0 = 0, m1 = 0, m2 = 0;
      for (int y = std::max(0, static_cast<int>(std::floor(y0)));
           y < std::min(height, static_cast<int>(std::ceil(y1))); ++y)
        for (int x = 0; x < width; ++x) {
          const double v = frame[static_cast<size_t>(y) * width + x];
          m0 += v;
          m1 += v * (x + 0.5);
          m2 += v * (x + 0.5) * (x + 0.5);
        }
      if (m0 > 1.0) {
        centre[i] = m1 / m0;
        spread[i] = std::max(1.0, 2.0 * std::sqrt(std::max(0.0, m2 / m0 - centre[i] * centre[i])));
        ok[i] = true;
      }
    }
    // Empty slices take their lower neighbour's values.
    for (int i = 1; i < n; ++i)
      if (!ok[i] && ok[i - 1]) {
        centre[i] = centre[i - 1];
        spread[i] = spread[i - 1];
        ok[i] = true;
      }
  };
  std::vector<double> unused;
  slice_moments(o.np, s.path, unused);
  slice_moments(o.nw, unused, s.width);
  return s;
}

void normalise(const uint8_t* frame, int width, int height, const FlameShape& s,
               const ShapeOptions& o, float* out) {
  const CubicSpline p = curve(s.path), w = curve(s.width);
  for (int r = 0; r < o.norm_height; ++r) {
    const double t = 1.0 - (r + 0.5) / o.norm_height;  // row 0 is the tip
    const double y = o.base_row - t * s.height;
    const double c = p(t), wd = std::max(1.0, w(t));
    for (int col = 0; col < o.norm_width; ++col) {
      const double u = ((col + 0.5) / o.norm_width * 2 - 1) * o.span;
      out[static_cast<size_t>(r) * o.norm_width + col] =
          bilinear(frame, width, height, c + u * wd, y);
    }
  }
}

void denormalise(const float* norm, const FlameShape& s, const ShapeOptions& o, int width,
                 int height, float* out) {
  const CubicSpline p = curve(s.path), w = curve(s.width);
  for (int y = 0; y < height; ++y) {
    const double t = (o.base_row - (y + 0.5)) / s.height;
    const double r = (1.0 - t) * o.norm_height;
    const double c = p(std::clamp(t, -0.1, 1.1)), wd = std::max(1.0, w(std::clamp(t, -0.1, 1.1)));
    for (int x = 0; x < width; ++x) {
      const double u = (x + 0.5 - c) / wd;
      const double col = (u / o.span + 1) / 2 * o.norm_width;
      out[static_cast<size_t>(y) * width + x] = bilinear(norm, o.norm_width, o.norm_height, col, r);
    }
  }
}

FlameShape LearningFlamesModel::shape_of(const Eigen::VectorXd& x) const {
  FlameShape s;
  s.path.assign(x.data(), x.data() + shape.np);
  s.width.assign(x.data() + shape.np, x.data() + shape.np + shape.nw);
  for (double& v : s.width) v = std::max(1.0, v);
  s.height = std::max(4.0, x[shape.np + shape.nw]);
  return s;
}

void LearningFlamesModel::render(const Eigen::VectorXd& x, int width, int height,
                                 float* out) const {
  const int n = shape.norm_width * shape.norm_height;
  Eigen::VectorXf norm = appearance.mean;
  for (int k = 0; k < ne && k < appearance.components(); ++k)
    norm += static_cast<float>(x[shape.np + shape.nw + 1 + k]) * appearance.basis.col(k);
  std::vector<float> img(norm.data(), norm.data() + n);
  for (float& v : img) v = std::max(0.0f, v);
  denormalise(img.data(), shape_of(x), shape, width, height, out);
}

LearningFlamesModel learn_flames(const Dataset& d, const LearningFlamesOptions& o) {
  LearningFlamesModel m;
  m.shape = o.shape;
  m.ne = o.ne;
  if (m.shape.base_row < 0) {
    const double br = d.options.contains("base_row") && d.options["base_row"].is_number()
                          ? d.options["base_row"].get<double>()
                          : 0.92;
    m.shape.base_row = br * d.height;
  }
  for (int f = 0; f < d.frames(); ++f)
    if (!d.multi_plume[f]) m.frames.push_back(f);
  const int n = static_cast<int>(m.frames.size());
  if (n < 8)
    throw std::invalid_argument(
        "Learning Flames needs at least 8 single-plume frames, the dataset has " +
        std::to_string(n));
  if (o.progress)
    o.progress("Learning Flames: shapes of " + std::to_string(n) + " single-plume frames");
  const ShapeOptions& so = m.shape;
  const size_t npx = static_cast<size_t>(so.norm_width) * so.norm_height;
  std::vector<FlameShape> shapes(n);
  std::vector<uint8_t> norm8(npx * n);
  std::vector<float> norm(npx);
  for (int i = 0; i < n; ++i) {
    shapes[i] = measure_shape(d.frame(m.frames[i]), d.width, d.height, so);
    normalise(d.frame(m.frames[i]), d.width, d.height, shapes[i], so, norm.data());
    for (size_t p = 0; p < npx; ++p)
      norm8[i * npx + p] = static_cast<uint8_t>(std::lround(std::clamp(norm[p], 0.0f, 255.0f)));
  }
  // Appearance: PCA of the normalised frames (held-out frames, by dataset index, left out).
  PcaOptions po;
  po.components = o.ne;
  std::vector<int> pos(d.frames(), -1);
  for (int i = 0; i < n; ++i) pos[m.frames[i]] = i;
  for (int f : o.holdout)
    if (f >= 0 && f < d.frames() && pos[f] >= 0) po.holdout.push_back(pos[f]);
  m.appearance = pca_snapshot(norm8.data(), so.norm_width, so.norm_height, n, po);
  m.params.resize(n, m.dim());
  for (int i = 0; i < n; ++i) {
    int c = 0;
    for (double v : shapes[i].path) m.params(i, c++) = v;
    for (double v : shapes[i].width) m.params(i, c++) = v;
    m.params(i, c++) = shapes[i].height;
    for (int k = 0; k < o.ne; ++k)
      m.params(i, c++) = k < m.appearance.components() ? m.appearance.weights(i, k) : 0.0;
  }
  if (o.learn_dynamics) {
    // Runs of consecutive single-plume frames within a clip are the ARP's sequences.
    std::vector<Eigen::MatrixXd> seqs;
    int start = 0;
    for (int i = 1; i <= n; ++i) {
      const bool breaks = i == n || m.frames[i] != m.frames[i - 1] + 1 || [&] {
        for (const auto& c : d.clips)
          if (m.frames[i] == c.first) return true;
        return false;
      }();
      if (breaks) {
        if (i - start >= o.arp.order + 8) seqs.push_back(m.params.middleRows(start, i - start));
        start = i;
      }
    }
    if (seqs.empty())
      throw NoFlameSequence("no run of consecutive single-plume frames is long enough for the ARP");
    ArpLearnOptions ao = o.arp;
    ao.progress = o.progress;
    m.dynamics = learn_arp(seqs, ao);
  }
  return m;
}

}  // namespace candela::tools

#include "model/flame_model.h"

namespace candela::tools {

LearningFlamesModel flames_from_model(const model::FlameModel& fm) {
  if (!fm.has_learning_flames)
    throw std::invalid_argument(fm.file().path() + ": the model has no Learning Flames part");
  const model::LearningFlamesModel& L = fm.flames;
  LearningFlamesModel m;
  m.shape.np = L.np;
  m.shape.nw = L.nw;
  m.shape.norm_width = L.width;
  m.shape.norm_height = L.height;
  m.shape.base_row = L.base_y;
  m.shape.span = L.span;
  m.ne = L.ne;
  const size_t npx = L.mean.pixels();
  m.appearance.width = L.width;
  m.appearance.height = L.height;
  m.appearance.mean.resize(static_cast<Eigen::Index>(npx));
  m.appearance.basis.resize(static_cast<Eigen::Index>(npx), L.ne);
  for (size_t p = 0; p < npx; ++p) {
    m.appearance.mean[static_cast<Eigen::Index>(p)] = L.mean.value(0, p);
    for (int k = 0; k < L.ne; ++k)
      m.appearance.basis(static_cast<Eigen::Index>(p), k) = L.eigen.value(k, p);
  }
  m.params =
      Eigen::Map<const Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
          L.params.data(), L.frames, L.dim)
          .cast<double>();
  Arp& a = m.dynamics.arp;
  a.order = L.order;
  for (int k = 0; k < L.order; ++k)
    a.A.push_back(
        Eigen::Map<const Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
            L.A.data() + static_cast<size_t>(k) * L.dim * L.dim, L.dim, L.dim)
            .cast<double>());
  a.d = Eigen::Map<const Eigen::VectorXf>(L.d.data(), L.dim).cast<double>();
  a.B = Eigen::Map<const Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
            L.B.data(), L.dim, L.dim)
            .cast<double>();
  return m;
}

}  // namespace candela::tools
