#include "pressure_solver.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace candela::fluid {
namespace {

double max_abs(const Grid2& g) { return g.max_abs(); }

double dot(const Grid2& a, const Grid2& b) {
  double s = 0.0;
  for (size_t k = 0; k < a.data.size(); ++k) s += a.data[k] * b.data[k];
  return s;
}

}  // namespace

PressureSolver::PressureSolver(int width, int height, Boundary boundary) : boundary_(boundary) {
  if (width < 1 || height < 1) throw std::invalid_argument("pressure grid must not be empty");
  if (!boundary.any_open())
    throw std::invalid_argument("pressure solver needs at least one open side");
  int w = width, h = height;
  for (;;) {
    Level lv;
    lv.w = w;
    lv.h = h;
    lv.x = Grid2(w, h);
    lv.b = Grid2(w, h);
    lv.r = Grid2(w, h);
    lv.diag.resize(static_cast<size_t>(w) * h);
    for (int j = 0; j < h; ++j)
      for (int i = 0; i < w; ++i) {
        double d = 0.0;
        d += (i > 0 || boundary.open_left) ? 1.0 : 0.0;
        d += (i < w - 1 || boundary.open_right) ? 1.0 : 0.0;
        d += (j > 0 || boundary.open_bottom) ? 1.0 : 0.0;
        d += (j < h - 1 || boundary.open_top) ? 1.0 : 0.0;
        lv.diag[static_cast<size_t>(j) * w + i] = d;
      }
    levels_.push_back(std::move(lv));
    // Stop where a dense factorisation is cheap (a few hundred cells).
    if (std::min(w, h) <= 3 || w * h <= 64) break;
    w = (w + 1) / 2;
    h = (h + 1) / 2;
  }
  factor_coarsest();
  r_ = Grid2(width, height);
  z_ = Grid2(width, height);
  p_ = Grid2(width, height);
  ap_ = Grid2(width, height);
}

void PressureSolver::apply_level(int l, const Grid2& x, Grid2& y) const {
  const Level& lv = levels_[l];
  const int w = lv.w, h = lv.h;
  for (int j = 0; j < h; ++j) {
    const double* row = &x.data[static_cast<size_t>(j) * w];
    const double* below = j > 0 ? row - w : nullptr;
    const double* above = j < h - 1 ? row + w : nullptr;
    double* out = &y.data[static_cast<size_t>(j) * w];
    const double* d = &lv.diag[static_cast<size_t>(j) * w];
    for (int i = 0; i < w; ++i) {
      double s = d[i] * row[i];
      if (i > 0) s -= row[i - 1];
      if (i < w - 1) s -= row[i + 1];
      if (below) s -= below[i];
      if (above) s -= above[i];
      out[i] = s;
    }
  }
}

// Red-black Gauss-Seidel on level l; colour_first = 0 starts with red cells
// ((i + j) even). Post-smoothing uses the reverse order, which keeps the
// V-cycle symmetric, as conjugate gradients needs.
void PressureSolver::smooth(int l, int colour_first, int sweeps) {
  Level& lv = levels_[l];
  const int w = lv.w, h = lv.h;
  for (int s = 0; s < sweeps; ++s) {
    for (int c = 0; c < 2; ++c) {
      const int colour = (colour_first + c) & 1;
      for (int j = 0; j < h; ++j) {
        double* row = &lv.x.data[static_cast<size_t>(j) * w];
        const double* below = j > 0 ? row - w : nullptr;
        const double* above = j < h - 1 ? row + w : nullptr;
        const double* b = &lv.b.data[static_cast<size_t>(j) * w];
        const double* d = &lv.diag[static_cast<size_t>(j) * w];
        for (int i = (j + colour) & 1; i < w; i += 2) {
          double s2 = b[i];
          if (i > 0) s2 += row[i - 1];
          if (i < w - 1) s2 += row[i + 1];
          if (below) s2 += below[i];
          if (above) s2 += above[i];
          row[i] = s2 / d[i];
        }
      }
    }
  }
}

void PressureSolver::vcycle(int l) {
  Level& lv = levels_[l];
  if (l + 1 == static_cast<int>(levels_.size())) {
    solve_coarsest();
    return;
  }
  lv.x.fill(0.0);
  smooth(l, 0, 2);
  apply_level(l, lv.x, lv.r);
  for (size_t k = 0; k < lv.r.data.size(); ++k) lv.r.data[k] = lv.b.data[k] - lv.r.data[k];
  // Restrict by summing the (up to four) children: the coarse stencil is the
  // same integer stencil on cells twice as large, so the sum is the matching
  // right-hand side for smooth errors.
  Level& c = levels_[l + 1];
  c.b.fill(0.0);
  for (int j = 0; j < lv.h; ++j)
    for (int i = 0; i < lv.w; ++i) c.b.at(i / 2, j / 2) += lv.r.at(i, j);
  vcycle(l + 1);
  for (int j = 0; j < lv.h; ++j)
    for (int i = 0; i < lv.w; ++i) lv.x.at(i, j) += c.x.at(i / 2, j / 2);
  smooth(l, 1, 2);
}

void PressureSolver::precondition(const Grid2& r, Grid2& z) {
  levels_[0].b.data = r.data;
  vcycle(0);
  z.data = levels_[0].x.data;
}

void PressureSolver::factor_coarsest() {
  Level& lv = levels_.back();
  const int n = lv.w * lv.h;
  // Dense A, then Cholesky A = L L^T (A is SPD because a side is open).
  std::vector<double> a(static_cast<size_t>(n) * n, 0.0);
  Grid2 e(lv.w, lv.h), col(lv.w, lv.h);
  for (int k = 0; k < n; ++k) {
    e.fill(0.0);
    e.data[k] = 1.0;
    apply_level(static_cast<int>(levels_.size()) - 1, e, col);
    for (int m = 0; m < n; ++m) a[static_cast<size_t>(m) * n + k] = col.data[m];
  }
  for (int j = 0; j < n; ++j) {
    double s = a[static_cast<size_t>(j) * n + j];
    for (int k = 0; k < j; ++k)
      s -= a[static_cast<size_t>(j) * n + k] * a[static_cast<size_t>(j) * n + k];
    if (s <= 0.0) throw std::runtime_error("coarsest pressure matrix is not positive definite");
    const double ljj = std::sqrt(s);
    a[static_cast<size_t>(j) * n + j] = ljj;
    for (int i = j + 1; i < n; ++i) {
      double t = a[static_cast<size_t>(i) * n + j];
      for (int k = 0; k < j; ++k)
        t -= a[static_cast<size_t>(i) * n + k] * a[static_cast<size_t>(j) * n + k];
      a[static_cast<size_t>(i) * n + j] = t / ljj;
    }
  }
  chol_ = std::move(a);
}

void PressureSolver::solve_coarsest() {
  Level& lv = levels_.back();
  const int n = lv.w * lv.h;
  std::vector<double>& x = lv.x.data;
  const std::vector<double>& b = lv.b.data;
  for (int i = 0; i < n; ++i) {
    double s = b[i];
    for (int k = 0; k < i; ++k) s -= chol_[static_cast<size_t>(i) * n + k] * x[k];
    x[i] = s / chol_[static_cast<size_t>(i) * n + i];
  }
  for (int i = n - 1; i >= 0; --i) {
    double s = x[i];
    for (int k = i + 1; k < n; ++k) s -= chol_[static_cast<size_t>(k) * n + i] * x[k];
    x[i] = s / chol_[static_cast<size_t>(i) * n + i];
  }
}

PressureStats PressureSolver::solve(const Grid2& b, Grid2& q, double tolerance,
                                    int max_iterations) {
  PressureStats st;
  apply(q, ap_);
  for (size_t k = 0; k < r_.data.size(); ++k) r_.data[k] = b.data[k] - ap_.data[k];
  st.residual = max_abs(r_);
  if (st.residual <= tolerance) {
    st.converged = true;
    return st;
  }
  precondition(r_, z_);
  p_.data = z_.data;
  double rz = dot(r_, z_);
  for (int it = 1; it <= max_iterations; ++it) {
    apply(p_, ap_);
    const double pap = dot(p_, ap_);
    if (!(pap > 0.0)) break;  // breakdown (round-off at convergence)
    const double alpha = rz / pap;
    for (size_t k = 0; k < q.data.size(); ++k) {
      q.data[k] += alpha * p_.data[k];
      r_.data[k] -= alpha * ap_.data[k];
    }
    st.iterations = it;
    st.residual = max_abs(r_);
    if (st.residual <= tolerance) {
      st.converged = true;
      break;
    }
    precondition(r_, z_);
    const double rz_new = dot(r_, z_);
    const double beta = rz_new / rz;
    rz = rz_new;
    for (size_t k = 0; k < p_.data.size(); ++k) p_.data[k] = z_.data[k] + beta * p_.data[k];
  }
  // Report the true residual, not the recurrence's estimate.
  apply(q, ap_);
  double m = 0.0;
  for (size_t k = 0; k < ap_.data.size(); ++k) m = std::max(m, std::fabs(b.data[k] - ap_.data[k]));
  st.residual = m;
  st.converged = m <= tolerance;
  return st;
}

}  // namespace candela::fluid
