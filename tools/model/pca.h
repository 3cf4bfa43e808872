// EigenFires: PCA of flame frames by the snapshot (Gram-matrix) method, which
// scales with the number of frames rather than pixels: G = Xc^T Xc (frames x
// frames), its eigenvectors V give the eigen-images U = Xc V S^-1, and the
// weights of the training frames come out of the same pass.
#pragma once

#include <Eigen/Dense>
#include <functional>
#include <string>
#include <vector>

#include "dataset.h"

namespace candela::tools {

struct PcaOptions {
  int components = 0;      // > 0: exactly this many (capped by the data)
  double variance = 0.99;  // else: the fewest components explaining this share
  int max_components = 128;
  std::vector<int> holdout;  // frames left out of the fit (still projected)
  std::function<void(const std::string&)> progress;
};

struct PcaResult {
  int width = 0, height = 0;
  Eigen::VectorXf mean;          // pixels
  Eigen::MatrixXf basis;         // pixels x E, orthonormal columns (eigen-images)
  Eigen::MatrixXf weights;       // all frames x E: basis^T (frame - mean)
  Eigen::VectorXd variance;      // every eigenvalue of the training covariance (/ n), descending
  double total_variance = 0;     // sum of variance
  Eigen::VectorXd frame_energy;  // all frames: ||frame - mean||^2
  std::vector<int> train;        // frames used for the fit
  int components() const { return static_cast<int>(basis.cols()); }
  // Mean squared error per pixel of frame f reconstructed from its first e weights.
  double mse(int frame, int e) const;
};

// Frames are 0..255 bytes; `frames` selects which (all when empty).
PcaResult pca_snapshot(const uint8_t* pixels, int width, int height, int frame_count,
                       const PcaOptions& opt);
inline PcaResult pca_snapshot(const Dataset& d, const PcaOptions& opt) {
  return pca_snapshot(d.pixels.data(), d.width, d.height, d.frames(), opt);
}

// PSNR (dB, peak 255) of the mean MSE over `frames` with e components.
double psnr_over(const PcaResult& r, const std::vector<int>& frames, int e);
double psnr_from_mse(double mse);

}  // namespace candela::tools
