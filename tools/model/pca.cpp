#include "pca.h"

#include <algorithm>
#include <cmath>
#ifdef _OPENMP
#include <omp.h>
#endif

namespace candela::tools {

namespace {
constexpr int kBlock =
    1024;  // pixels per block: a block of all frames stays in cache-friendly panels
}

double PcaResult::mse(int frame, int e) const {
  double r = frame_energy[frame];
  for (int k = 0; k < e && k < components(); ++k)
    r -= static_cast<double>(weights(frame, k)) * weights(frame, k);
  return std::max(0.0, r) / static_cast<double>(mean.size());
}

double psnr_from_mse(double mse) { return 10.0 * std::log10(255.0 * 255.0 / std::max(mse, 1e-12)); }

double psnr_over(const PcaResult& r, const std::vector<int>& frames, int e) {
  double s = 0;
  for (int f : frames) s += r.mse(f, e);
  return psnr_from_mse(s / std::max<size_t>(1, frames.size()));
}

PcaResult pca_snapshot(const uint8_t* pixels, int width, int height, int frame_count,
                       const PcaOptions& opt) {
  PcaResult r;
  r.width = width;
  r.height = height;
  const Eigen::Index npx = static_cast<Eigen::Index>(width) * height;
  std::vector<uint8_t> held(frame_count, 0);
  for (int f : opt.holdout)
    if (f >= 0 && f < frame_count) held[f] = 1;
  for (int f = 0; f < frame_count; ++f)
    if (!held[f]) r.train.push_back(f);
  const int n = static_cast<int>(r.train.size());
  if (n < 2) throw std::invalid_argument("PCA needs at least two training frames");
  auto say = [&](const std::string& s) {
    if (opt.progress) opt.progress(s);
  };

  // Mean of the training frames.
  Eigen::VectorXd mean_d = Eigen::VectorXd::Zero(npx);
  for (int f : r.train) {
    const uint8_t* src = pixels + static_cast<size_t>(f) * npx;
    for (Eigen::Index p = 0; p < npx; ++p) mean_d[p] += src[p];
  }
  r.mean = (mean_d / n).cast<float>();

  const int blocks = static_cast<int>((npx + kBlock - 1) / kBlock);
  // Centred block of frames `which` for pixels [p0, p0 + rows): rows x frames, column-major,
  // so each frame's run of pixels is one contiguous copy.
  auto fill = [&](Eigen::MatrixXf& blk, const std::vector<int>& which, Eigen::Index p0,
                  Eigen::Index rows) {
    blk.resize(rows, static_cast<Eigen::Index>(which.size()));
    for (size_t j = 0; j < which.size(); ++j) {
      const uint8_t* src = pixels + static_cast<size_t>(which[j]) * npx + p0;
      float* dst = blk.col(static_cast<Eigen::Index>(j)).data();
      const float* m = r.mean.data() + p0;
      for (Eigen::Index i = 0; i < rows; ++i) dst[i] = static_cast<float>(src[i]) - m[i];
    }
  };

  // Pass 1: Gram matrix G = Xc^T Xc (lower triangle). Each block's share is
  // added in block order (`ordered`), so the sum, and the model, are the same
  // bytes from run to run and on any number of threads.
  say("PCA: Gram matrix of " + std::to_string(n) + " frames x " + std::to_string(npx) + " pixels");
  Eigen::MatrixXd gram = Eigen::MatrixXd::Zero(n, n);
#pragma omp parallel
  {
    Eigen::MatrixXf g(n, n), blk;
#pragma omp for ordered schedule(dynamic, 1)
    for (int b = 0; b < blocks; ++b) {
      const Eigen::Index p0 = static_cast<Eigen::Index>(b) * kBlock;
      fill(blk, r.train, p0, std::min<Eigen::Index>(kBlock, npx - p0));
      g.setZero();
      g.selfadjointView<Eigen::Lower>().rankUpdate(blk.transpose());
#pragma omp ordered
      gram += g.cast<double>();
    }
  }

  say("PCA: eigen-decomposition of the " + std::to_string(n) + "x" + std::to_string(n) +
      " Gram matrix");
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(gram.selfadjointView<Eigen::Lower>());
  if (es.info() != Eigen::Success) throw std::runtime_error("PCA: eigen-decomposition failed");
  // Descending order; eigenvalues of G are squared singular values.
  Eigen::VectorXd sv2 = es.eigenvalues().reverse().cwiseMax(0.0);
  Eigen::MatrixXd vecs = es.eigenvectors().rowwise().reverse();
  r.variance = sv2 / n;
  r.total_variance = r.variance.sum();
  int rank = 0;
  while (rank < n && sv2[rank] > sv2[0] * 1e-10) ++rank;
  if (rank == 0)  // e.g. footage whose every pixel the ingest's background level took off
    throw std::invalid_argument(
        "PCA: the training frames are all the same picture (nothing varies), so there is "
        "nothing to learn; look at the frames (a background level that takes off the whole "
        "flame makes them all black)");
  int e = 0;
  if (opt.components > 0) {
    e = opt.components;
  } else {
    double acc = 0;
    while (e < rank && acc < opt.variance * r.total_variance) acc += r.variance[e++];
  }
  // max_components caps only what --variance chooses: an explicit count is
  // taken as asked (it was silently cut to the cap, 128, before).
  if (opt.components <= 0 && opt.max_components > 0) e = std::min(e, opt.max_components);
  e = std::clamp(e, 1, std::max(1, rank));
  if (opt.components > rank)
    say("PCA: " + std::to_string(opt.components) + " components asked, the frames span only " +
        std::to_string(rank));

  // Pass 2: eigen-images U = Xc V S^-1 and the weights of all frames W = X_all^T U.
  say("PCA: " + std::to_string(e) + " eigen-images and weights of " + std::to_string(frame_count) +
      " frames");
  Eigen::MatrixXf proj(n, e);  // V S^-1
  for (int k = 0; k < e; ++k) proj.col(k) = (vecs.col(k) / std::sqrt(sv2[k])).cast<float>();
  std::vector<int> all(frame_count);
  for (int f = 0; f < frame_count; ++f) all[f] = f;
  std::vector<int> train_col(n);  // position of each training frame among all frames
  for (int j = 0; j < n; ++j) train_col[j] = r.train[j];
  r.basis.resize(npx, e);
  r.weights = Eigen::MatrixXf::Zero(frame_count, e);
  r.frame_energy = Eigen::VectorXd::Zero(frame_count);
#pragma omp parallel
  {
    Eigen::MatrixXf blk, w;
    Eigen::VectorXd energy;
#pragma omp for ordered schedule(dynamic, 1)
    for (int b = 0; b < blocks; ++b) {
      const Eigen::Index p0 = static_cast<Eigen::Index>(b) * kBlock;
      const Eigen::Index rows = std::min<Eigen::Index>(kBlock, npx - p0);
      fill(blk, all, p0, rows);
      r.basis.middleRows(p0, rows).noalias() = blk(Eigen::all, train_col) * proj;
      w.noalias() = blk.transpose() * r.basis.middleRows(p0, rows);
      energy = blk.colwise().squaredNorm().transpose().cast<double>();
#pragma omp ordered
      {  // in block order, as pass 1
        r.weights += w;
        r.frame_energy += energy;
      }
    }
  }
  return r;
}

}  // namespace candela::tools
