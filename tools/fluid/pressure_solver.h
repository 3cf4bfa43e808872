// Pressure projection for a 2-D MAC grid: solves A q = b, where A is the
// 5-point Laplacian stencil (diagonal = number of non-wall neighbours, -1 per
// interior neighbour; an open side is a ghost cell held at q = 0) and b is
// minus the net outflow of each cell. Conjugate gradients preconditioned by
// one geometric multigrid V-cycle (red-black Gauss-Seidel smoothing, piecewise
// constant transfer, dense Cholesky on the coarsest grid): converges in a
// handful of iterations at any grid size, unlike plain Jacobi.
#pragma once

#include <vector>

#include "grid2.h"

namespace candela::fluid {

struct Boundary {
  bool open_left = true;
  bool open_right = true;
  bool open_top = true;
  bool open_bottom = false;  // the floor the fire burns on
  bool any_open() const { return open_left || open_right || open_top || open_bottom; }
};

struct PressureStats {
  int iterations = 0;
  double residual = 0.0;  // max |b - A q| at exit
  bool converged = false;
};

class PressureSolver {
 public:
  // Requires at least one open side (otherwise A is singular).
  PressureSolver(int width, int height, Boundary boundary);

  // Improves q (used as the first guess) until max|b - A q| <= tolerance or
  // max_iterations is reached.
  PressureStats solve(const Grid2& b, Grid2& q, double tolerance, int max_iterations);

  // y = A x (exposed for tests).
  void apply(const Grid2& x, Grid2& y) const { apply_level(0, x, y); }
  int levels() const { return static_cast<int>(levels_.size()); }

 private:
  struct Level {
    int w = 0, h = 0;
    Grid2 x, b, r;
    std::vector<double> diag;  // per cell
  };
  void apply_level(int l, const Grid2& x, Grid2& y) const;
  void smooth(int l, int colour_first, int sweeps);
  void vcycle(int l);
  void precondition(const Grid2& r, Grid2& z);
  void factor_coarsest();
  void solve_coarsest();

  Boundary boundary_;
  std::vector<Level> levels_;
  std::vector<double> chol_;  // lower-triangular factor of the coarsest A
  Grid2 r_, z_, p_, ap_;
};

}  // namespace candela::fluid
