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

  // Bilinear sample at (x, y) in index units (sample (i, j) sits at (i, j)),
  // clamped to the array: points outside read the nearest edge value.
  double sample(double x, double y) const {
    x = std::clamp(x, 0.0, static_cast<double>(width - 1));
    y = std::clamp(y, 0.0, static_cast<double>(height - 1));
    const int i0 = std::min(static_cast<int>(x), width - 2 < 0 ? 0 : width - 2);
    const int j0 = std::min(static_cast<int>(y), height - 2 < 0 ? 0 : height - 2);
    const int i1 = std::min(i0 + 1, width - 1);
    const int j1 = std::min(j0 + 1, height - 1);
    const double fx = x - i0;
    const double fy = y - j0;
    const double a = at(i0, j0) + (at(i1, j0) - at(i0, j0)) * fx;
    const double b = at(i0, j1) + (at(i1, j1) - at(i0, j1)) * fx;
    return a + (b - a) * fy;
  }

  double max_abs() const {
    double m = 0.0;
    for (double v : data) m = std::max(m, std::fabs(v));
    return m;
  }
};

}  // namespace candela::fluid
