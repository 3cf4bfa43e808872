// The EigenFires paper's transitions in weight space without Eigen, for the
// device (story planning at start-up) and candela-tool alike: low-pass
// blending, Direct Bridging and End Growing Connection (Table 1), the same
// algorithms as tools/model/transitions.h (tests compare the two).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "model/flame_model.h"

namespace candela::story {

// A model's per-frame weights (frames x stride floats) and its clips.
class WeightTable {
 public:
  // dims: components that distances use (the first ones; <= 0 or more than
  // stride: all).
  WeightTable(std::span<const float> weights, int stride, int frames,
              const std::vector<model::ClipInfo>& clips, int dims = 0);
  static WeightTable of(const model::FlameModel& m, int dims = 0);

  int frames() const { return frames_; }
  int stride() const { return stride_; }
  int dims() const { return dims_; }
  const float* row(int frame) const { return w_.data() + static_cast<size_t>(frame) * stride_; }
  // Euclidean distance over the first dims() components (summed in double, in order).
  float distance(int a, int b) const { return distance(row(a), row(b)); }
  float distance(const float* a, const float* b) const;
  int clip_of(int f) const { return clip_of_[static_cast<size_t>(f)]; }
  int clip_first(int c) const { return clip_first_[static_cast<size_t>(c)]; }
  int clip_end(int c) const { return clip_end_[static_cast<size_t>(c)]; }
  // The median distance between consecutive frames of the same clip: the
  // model's ordinary step, the unit of seam ratios.
  float median_step() const;
  // The q-quantile (0..1) of those steps, in median steps.
  float step_quantile_ratio(double q) const;

  // Work done with the table, in component operations (a distance over 50
  // components is 50), and a limit past which charge() and distance() throw
  // WorkLimitReached: what bounds a story's planning (story_plan.h).
  void set_work_limit(uint64_t limit) { work_limit_ = limit; }
  uint64_t work() const { return work_; }
  void charge(uint64_t ops) const {
    work_ += ops;
    if (work_ > work_limit_) throw WorkLimitReached(work_limit_);
  }

  struct WorkLimitReached : std::runtime_error {
    explicit WorkLimitReached(uint64_t limit)
        : std::runtime_error("more than " + std::to_string(limit) + " component operations") {}
  };

 private:
  std::span<const float> w_;
  int stride_, dims_, frames_;
  mutable uint64_t work_ = 0;
  uint64_t work_limit_ = UINT64_MAX;
  std::vector<int> clip_of_, clip_first_, clip_end_;
};

struct PathOptions {
  int steps = 20;       // N
  float theta_min = 0;  // smallest step allowed
  int reject_tail = 3;  // frames just before alpha / after beta are not used
};

struct FramePath {
  bool found = false;
  std::string how;        // as tools::Transition::how
  std::vector<int> path;  // alpha, the inserted frames, beta
};

FramePath direct_bridging(const WeightTable& s, int alpha, int beta, const PathOptions& o);
FramePath end_growing(const WeightTable& s, int alpha, int beta, const PathOptions& o);
void optimise_path(const WeightTable& s, std::vector<int>& path, float theta_min);

// Low-pass joint of T1 (its last frames t1, in order) and T2 (its first frames
// t2): the new weights (stride floats each) of t1's last two frames and t2's
// first two, the first `filtered` components filtered with `kernel` (T2's side
// mirrored), the rest unchanged. t1 and t2 hold at least two frames each.
std::vector<float> lowpass_rows(const WeightTable& s, std::span<const int> t1,
                                std::span<const int> t2, std::array<float, 3> kernel, int filtered);

}  // namespace candela::story
