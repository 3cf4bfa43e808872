// A dense 2-D array of doubles, row-major, row 0 at the BOTTOM (y points up,
// as in the simulation). Images are converted at the edges of the library.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace candela::fluid {

struct Grid2 {
  int width = 0;
  int height = 0;
  std::vector<double> data;

  Grid2() = default;
  Grid2(int w, int h, double fill = 0.0)
      : width(w), height(h), data(static_cast<size_t>(w) * h, fill) {}

  double& at(int i, int j) { return data[static_cast<size_t>(j) * width + i]; }
  double at(int i, int j) const { return data[static_cast<size_t>(j) * width + i]; }
  double clamped(int i, int j) const {
    return at(std::clamp(i, 0, width - 1), std::clamp(j, 0, height - 1));
  }
  void fill(double v) { std::fill(data.begin(), data.end(), v); }

  // The four samples around (x, y), clamped to the array: the first's
  // address, the steps to its right and lower neighbours (0 where the array
  // is one sample wide or tall) and where (x, y) lies between them.
  struct Corner {
    const double* p;
    int di;
    size_t dj;
    double fx, fy;
  };
  [[gnu::always_inline]] inline Corner corner(double x, double y) const {
    const double mx = width - 1, my = height - 1;
    x = x < 0.0 ? 0.0 : (x > mx ? mx : x);
    y = y < 0.0 ? 0.0 : (y > my ? my : y);
    int i0 = static_cast<int>(x), j0 = static_cast<int>(y);
    i0 -= (i0 == width - 1 && i0 > 0);
    j0 -= (j0 == height - 1 && j0 > 0);
    return {&data[static_cast<size_t>(j0) * width + i0], width > 1 ? 1 : 0,
            height > 1 ? static_cast<size_t>(width) : 0, x - i0, y - j0};
  }

  // Bilinear sample at (x, y) in index units (sample (i, j) sits at (i, j)),
  // clamped to the array: points outside read the nearest edge value.
  // Hot path of advection: kept inline and branch-light.
  [[gnu::always_inline]] inline double sample(double x, double y) const {
    const Corner c = corner(x, y);
    const double* p = c.p;
    const double a = p[0] + (p[c.di] - p[0]) * c.fx;
    const double b = p[c.dj] + (p[c.dj + c.di] - p[c.dj]) * c.fx;
    return a + (b - a) * c.fy;
  }

  // The smallest and largest of the four values sample(x, y) blends: the
  // bounds MacCormack advection clamps to, so it adds no new extrema.
  void sample_range(double x, double y, double& lo, double& hi) const {
    const Corner c = corner(x, y);
    const double* p = c.p;
    const int di = c.di;
    const size_t dj = c.dj;
    lo = std::min(std::min(p[0], p[di]), std::min(p[dj], p[dj + di]));
    hi = std::max(std::max(p[0], p[di]), std::max(p[dj], p[dj + di]));
  }

  double max_abs() const {
    double m = 0.0;
    for (double v : data) m = std::max(m, std::fabs(v));
    return m;
  }
};

}  // namespace candela::fluid
