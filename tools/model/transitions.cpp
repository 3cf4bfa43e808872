#include "transitions.h"

#include <algorithm>
#include <cmath>
#include <span>
#include <stdexcept>

#include "story/weight_transitions.h"

namespace candela::tools {

WeightSpace WeightSpace::from(const Eigen::MatrixXf& weights,
                              const std::vector<model::ClipInfo>& clips, int components) {
  WeightSpace s;
  s.clips = clips;
  const int e = components > 0 ? std::min<int>(components, static_cast<int>(weights.cols()))
                               : static_cast<int>(weights.cols());
  s.w = weights.leftCols(e);
  s.cols = s.w.transpose();
  s.clip_of.assign(weights.rows(), 0);
  for (size_t c = 0; c < clips.size(); ++c) {
    s.clip_first.push_back(clips[c].first);
    s.clip_end.push_back(clips[c].first + clips[c].count);
    for (int f = clips[c].first; f < clips[c].first + clips[c].count && f < weights.rows(); ++f)
      s.clip_of[f] = static_cast<int>(c);
  }
  if (clips.empty()) {
    s.clip_first.push_back(0);
    s.clip_end.push_back(static_cast<int>(weights.rows()));
  }
  return s;
}

namespace {
// The firmware's planner (story/weight_transitions.h) over this space: its
// columns are the frames' weights, one after another.
story::WeightTable table_of(const WeightSpace& s) {
  return story::WeightTable(
      std::span<const float>(s.cols.data(), static_cast<size_t>(s.cols.size())),
      static_cast<int>(s.cols.rows()), s.frames(), s.clips);
}
Transition transition_of(story::FramePath p) {
  return Transition{p.found, std::move(p.how), std::move(p.path)};
}
story::PathOptions path_options(const TransitionOptions& o) {
  return {o.steps, o.theta_min, o.reject_tail};
}
}  // namespace

Eigen::MatrixXf lowpass_transition(const Eigen::MatrixXf& weights, const std::vector<int>& t1,
                                   const std::vector<int>& t2, const std::vector<float>& kernel,
                                   int filtered) {
  if (t1.size() < 2 || t2.size() < 2 || kernel.size() != 3)
    throw std::invalid_argument(
        "low-pass transition needs two frames on each side and a 3-tap kernel");
  using RowMajor = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  const RowMajor rows = weights;
  const int e = static_cast<int>(weights.cols());
  const story::WeightTable s(std::span<const float>(rows.data(), static_cast<size_t>(rows.size())),
                             e, static_cast<int>(weights.rows()), {});
  const std::vector<float> out =
      story::lowpass_rows(s, t1, t2, {kernel[0], kernel[1], kernel[2]}, filtered);
  return Eigen::Map<const RowMajor>(out.data(), 4, e);
}

Transition direct_bridging(const WeightSpace& s, int alpha, int beta, const TransitionOptions& o) {
  return transition_of(story::direct_bridging(table_of(s), alpha, beta, path_options(o)));
}

Transition end_growing(const WeightSpace& s, int alpha, int beta, const TransitionOptions& o) {
  return transition_of(story::end_growing(table_of(s), alpha, beta, path_options(o)));
}

void optimise_path(const WeightSpace& s, std::vector<int>& path, float theta_min) {
  story::optimise_path(table_of(s), path, theta_min);
}

MotionGraphData build_motion_graph(const WeightSpace& s, const MotionGraphOptions& o) {
  const int n = s.frames();
  MotionGraphData g;
  // All pairwise distances from the Gram matrix of the weights.
  const Eigen::VectorXf sq = s.w.rowwise().squaredNorm();
  Eigen::MatrixXf dist = s.w * s.w.transpose();
  dist = ((-2.0f * dist).colwise() + sq).rowwise() + sq.transpose();
  dist = dist.cwiseMax(0.0f).cwiseSqrt();
  std::vector<float> steps;
  for (int i = 0; i + 1 < n; ++i)
    if (s.clip_of[i] == s.clip_of[i + 1]) steps.push_back(dist(i, i + 1));
  if (steps.empty()) steps.push_back(dist.maxCoeff());
  std::nth_element(steps.begin(), steps.begin() + steps.size() / 2, steps.end());
  g.median_step = steps[steps.size() / 2];
  g.theta_min = o.theta_min > 0 ? o.theta_min : 0.5f * g.median_step;
  const float max_step = std::max(g.theta_min, o.max_step_factor * g.median_step);
  g.offsets.push_back(0);
  std::vector<std::pair<float, int>> cand;
  for (int i = 0; i < n; ++i) {
    const int c = s.clip_of[i];
    const bool has_next = i + 1 < s.clip_end[c];
    if (has_next) {
      g.successors.push_back(i + 1);
      g.cost.push_back(s.distance(i, i + 1));
    }
    cand.clear();
    for (int j = 0; j < n; ++j) {
      if (s.clip_of[j] == c && std::abs(j - i) < o.min_jump) continue;
      const float step = dist(i, j);
      if (step < g.theta_min || step > max_step) continue;
      // Rank by how much j looks like the frame that would naturally follow.
      cand.push_back({has_next ? dist(i + 1, j) : step, j});
    }
    std::sort(cand.begin(), cand.end());
    for (size_t k = 0; k < cand.size() && static_cast<int>(k) < o.max_successors; ++k) {
      g.successors.push_back(cand[k].second);
      g.cost.push_back(s.distance(i, cand[k].second));
    }
    if (g.successors.size() == static_cast<size_t>(g.offsets.back())) {
      // A dead end (last frame, nothing similar): take the nearest real step away.
      int best = -1;
      for (int j = 0; j < n; ++j) {
        if ((s.clip_of[j] == c && std::abs(j - i) < o.min_jump) || j == i) continue;
        if (best < 0 ||
            std::abs(dist(i, j) - g.median_step) < std::abs(dist(i, best) - g.median_step))
          best = j;
      }
      if (best < 0) best = s.clip_first[c];
      g.successors.push_back(best);
      g.cost.push_back(s.distance(i, best));
    }
    g.offsets.push_back(static_cast<int32_t>(g.successors.size()));
  }
  return g;
}

}  // namespace candela::tools
