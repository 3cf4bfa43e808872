// The `arp` driver (Learning Flames): the learned auto-regressive process
//   x_t = A_1 x_{t-1} + ... + A_K x_{t-K} + d + B w_t,   w_t ~ N(0, I)
// run forward from a seed, one state per model frame.
//
// Determinism: the state is IEEE-754 binary32 and every operation is a single
// correctly rounded + or * done in the fixed order written below; the build
// uses -ffp-contract=off, so no compiler fuses a*b+c into an FMA (which would
// round once instead of twice and differ between x86 and ARM). No libm call is
// used: the Gaussian noise is the Irwin-Hall sum of twelve 24-bit uniforms
// from Pcg32 (exact integer arithmetic, then one exact int->float conversion
// and a power-of-two scale), so a seed gives bit-identical states anywhere.
//
// Order of operations (each sum starts at 0.0f and adds j = 0, 1, ... in turn):
//   y_i = (((sum_j A_1[i][j] x_{t-1}[j]) + sum_j A_2[i][j] x_{t-2}[j]) + ... ) + d_i
//   x_t[i] = clamp(y_i + sum_j B[i][j] w_t[j], lo_i, hi_i)
// The clamp (training range widened by half its span each way) keeps a learned
// process that is slightly unstable from running away; tests check it rarely bites.
#pragma once

#include <array>
#include <cstdint>
#include <span>

#include "core/random.h"
#include "model/flame_model.h"

namespace candela {
struct ArpView {
  int dim = 0, order = 2;
  std::span<const float> A, d, B;   // K*D*D (A_k[i][j] at (k*D + i)*D + j), D, D*D
  std::span<const float> training;  // T x D: the training parameter sequence
  int frames() const { return dim > 0 ? static_cast<int>(training.size()) / dim : 0; }
  // The learned process of a model file (views into it; the model outlives them).
  static ArpView of(const model::LearningFlamesModel& flames);
};

class ArpProcess {
 public:
  // The model reader refuses more (model/flame_model.h), so every loaded model plays.
  static constexpr int kMaxDim = model::kMaxArpDim;
  static constexpr int kMaxOrder = model::kMaxArpOrder;

  // Starts from K consecutive training states picked by the seed.
  ArpProcess(const ArpView& view, uint64_t seed);
  // Advances one model frame; returns the new state.
  std::span<const float> step();
  std::span<const float> state() const { return {x_[0].data(), static_cast<size_t>(dim_)}; }
  // One N(0,1) sample (Irwin-Hall, 12 terms): exposed for tests.
  static float gaussian(Pcg32& rng);
  uint64_t clamped() const { return clamped_; }

 private:
  ArpView v_;
  int dim_, order_;
  Pcg32 rng_;
  std::array<std::array<float, kMaxDim>, kMaxOrder> x_{};  // x_[0] newest
  std::array<float, kMaxDim> w_{}, lo_{}, hi_{};
  uint64_t clamped_ = 0;
};

}  // namespace candela
