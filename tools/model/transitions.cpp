#include "transitions.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <unordered_set>

namespace candela::tools {

WeightSpace WeightSpace::from(const Eigen::MatrixXf& weights,
                              const std::vector<model::ClipInfo>& clips, int components) {
  WeightSpace s;
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

Eigen::MatrixXf lowpass_transition(const Eigen::MatrixXf& weights, const std::vector<int>& t1,
                                   const std::vector<int>& t2, const std::vector<float>& kernel,
                                   int filtered) {
  if (t1.size() < 2 || t2.size() < 2 || kernel.size() != 3)
    throw std::invalid_argument(
        "low-pass transition needs two frames on each side and a 3-tap kernel");
  std::vector<int> seq(t1.end() - 3 < t1.begin() ? t1.begin() : t1.end() - 3, t1.end());
  const int n1 = static_cast<int>(seq.size());
  seq.insert(seq.end(), t2.begin(), t2.begin() + std::min<size_t>(3, t2.size()));
  const int e = std::min<int>(filtered, static_cast<int>(weights.cols()));
  Eigen::MatrixXf out(4, weights.cols());
  for (int r = 0; r < 4; ++r) {
    const int i = n1 - 2 + r;  // position in seq
    out.row(r) = weights.row(seq[i]);
    // T1's side uses the kernel as given, T2's side its mirror image.
    Eigen::RowVectorXf acc = Eigen::RowVectorXf::Zero(e);
    for (int j = 0; j < 3; ++j) {
      const float k = r < 2 ? kernel[j] : kernel[2 - j];
      const int at = std::clamp(i + j - 1, 0, static_cast<int>(seq.size()) - 1);
      acc += k * weights.row(seq[at]).head(e);
    }
    out.row(r).head(e) = acc;
  }
  return out;
}

namespace {

// Frames a transition may not use: its ends, and the last few frames that lead
// into alpha and follow beta in their clips.
std::vector<uint8_t> initial_rejections(const WeightSpace& s, int alpha, int beta, int tail) {
  std::vector<uint8_t> used(s.frames(), 0);
  used[alpha] = used[beta] = 1;
  for (int i = 1; i <= tail; ++i) {
    if (alpha - i >= s.clip_first[s.clip_of[alpha]]) used[alpha - i] = 1;
    if (beta + i < s.clip_end[s.clip_of[beta]]) used[beta + i] = 1;
  }
  return used;
}

void check_ends(const WeightSpace& s, int alpha, int beta) {
  if (alpha < 0 || beta < 0 || alpha >= s.frames() || beta >= s.frames())
    throw std::out_of_range("transition ends must be frames of the model");
}

}  // namespace

Transition direct_bridging(const WeightSpace& s, int alpha, int beta, const TransitionOptions& o) {
  check_ends(s, alpha, beta);
  Transition t;
  std::vector<uint8_t> used = initial_rejections(s, alpha, beta, o.reject_tail);
  t.path.push_back(alpha);
  const Eigen::VectorXf a = s.cols.col(alpha), b = s.cols.col(beta);
  for (int i = 1; i <= o.steps; ++i) {
    const Eigen::VectorXf target =
        a + (b - a) * (static_cast<float>(i) / static_cast<float>(o.steps + 1));
    int best = -1;
    float best_d = 0;
    for (int f = 0; f < s.frames(); ++f) {
      if (used[f] || s.distance(t.path.back(), f) < o.theta_min) continue;
      const float d = (s.cols.col(f) - target).squaredNorm();
      if (best < 0 || d < best_d) {
        best = f;
        best_d = d;
      }
    }
    if (best < 0) break;
    used[best] = 1;
    t.path.push_back(best);
  }
  t.path.push_back(beta);
  t.found = true;
  t.how = "bridged";
  return t;
}

Transition end_growing(const WeightSpace& s, int alpha, int beta, const TransitionOptions& o) {
  check_ends(s, alpha, beta);
  Transition t;
  const float theta = o.theta_min;
  std::vector<uint8_t> used = initial_rejections(s, alpha, beta, o.reject_tail);
  std::vector<int> from_a{alpha}, from_b{beta};
  std::vector<int> sa, sb;
  std::vector<float> da(s.frames()), db(s.frames());
  auto join = [&](int shared) {
    t.path = from_a;
    if (shared >= 0) t.path.push_back(shared);
    t.path.insert(t.path.end(), from_b.rbegin(), from_b.rend());
    t.found = true;
  };
  for (int step = 0; step < std::max(1, o.steps / 2); ++step) {
    const int a = from_a.back(), b = from_b.back();
    const float D = s.distance(a, b);
    if (D < theta) {
      t.how = "gap below theta_min";
      join(-1);
      optimise_path(s, t.path, theta);
      return t;
    }
    // Candidates near each end: unused, a real step (>= theta) and closer than the other end.
    sa.clear();
    sb.clear();
    for (int f = 0; f < s.frames(); ++f) {
      if (used[f]) continue;
      da[f] = (s.cols.col(a) - s.cols.col(f)).norm();
      db[f] = (s.cols.col(b) - s.cols.col(f)).norm();
      if (da[f] >= theta && da[f] < D) sa.push_back(f);
      if (db[f] >= theta && db[f] < D) sb.push_back(f);
    }
    // Sorted lazily: the walk below rarely goes past the first few dozen.
    size_t sorted_a = 0, sorted_b = 0;
    auto by_a = [&](int x, int y) { return da[x] < da[y]; };
    auto by_b = [&](int x, int y) { return db[x] < db[y]; };
    auto extend = [](std::vector<int>& v, size_t& sorted, size_t need, auto cmp) {
      if (need < sorted) return;
      const size_t upto = std::min(v.size(), std::max<size_t>(32, 2 * need + 1));
      std::partial_sort(v.begin() + static_cast<ptrdiff_t>(sorted),
                        v.begin() + static_cast<ptrdiff_t>(upto), v.end(), cmp);
      sorted = upto;
    };
    // Table 1: walk both sorted lists; a frame near both ends joins them.
    std::unordered_set<int> seen_a, seen_b;
    size_t j = 0, k = 0;
    bool found_step = false;
    while (j < sa.size() && k < sb.size() && !found_step) {
      extend(sa, sorted_a, j, by_a);
      extend(sb, sorted_b, k, by_b);
      const int aj = sa[j], bk = sb[k];
      seen_a.insert(aj);
      seen_b.insert(bk);
      int shared = aj == bk || seen_b.count(aj) ? aj : (seen_a.count(bk) ? bk : -1);
      if (shared >= 0) {
        t.how = "shared image";
        join(shared);
        optimise_path(s, t.path, theta);
        return t;
      }
      const float d12 = s.distance(aj, bk), d1 = db[aj] /* |b - aj| */, d2 = da[bk] /* |a - bk| */;
      if (D - d12 < theta) {
        // Not enough progress: move on in the list whose candidate strays.
        const bool short_to_a = d2 - D <= theta;
        const bool short_to_b = d1 - D <= theta;
        if (short_to_a && short_to_b) {
          ++j;
          ++k;
        } else {
          if (!short_to_a) ++k;
          if (!short_to_b) ++j;
        }
      } else {
        from_a.push_back(aj);
        from_b.push_back(bk);
        used[aj] = used[bk] = 1;
        found_step = true;
      }
    }
    if (!found_step) {
      t.how = "no step closes the gap by theta_min";
      t.path = from_a;
      t.path.insert(t.path.end(), from_b.rbegin(), from_b.rend());
      return t;
    }
  }
  const int a = from_a.back(), b = from_b.back();
  if (s.distance(a, b) < theta) {
    t.how = "gap below theta_min";
    join(-1);
    optimise_path(s, t.path, theta);
    return t;
  }
  t.how = "not connected within " + std::to_string(o.steps) + " steps";
  t.path = from_a;
  t.path.insert(t.path.end(), from_b.rbegin(), from_b.rend());
  return t;
}

void optimise_path(const WeightSpace& s, std::vector<int>& path, float theta_min) {
  bool changed = true;
  while (changed && path.size() > 2) {
    changed = false;
    // First merge steps below theta_min, dropping whichever interior frame
    // leaves the smaller largest step.
    for (size_t i = 0; i + 1 < path.size() && !changed; ++i) {
      if (s.distance(path[i], path[i + 1]) >= theta_min) continue;
      auto cost_without = [&](size_t r) {
        return std::max(
            s.distance(path[r - 1], path[r + 1]),
            std::max(r >= 2 ? s.distance(path[r - 2], path[r - 1]) : 0.0f,
                     r + 2 < path.size() ? s.distance(path[r + 1], path[r + 2]) : 0.0f));
      };
      size_t drop = 0;
      if (i > 0 && i + 1 < path.size() - 1)
        drop = cost_without(i) <= cost_without(i + 1) ? i : i + 1;
      else if (i > 0)
        drop = i;
      else if (i + 1 < path.size() - 1)
        drop = i + 1;
      if (drop) {
        path.erase(path.begin() + static_cast<ptrdiff_t>(drop));
        changed = true;
      }
    }
    // Then detours: a frame further from both neighbours than they are from each other.
    for (size_t i = 1; i + 1 < path.size() && !changed; ++i) {
      const float skip = s.distance(path[i - 1], path[i + 1]);
      if (skip >= theta_min &&
          skip < std::min(s.distance(path[i - 1], path[i]), s.distance(path[i], path[i + 1]))) {
        path.erase(path.begin() + static_cast<ptrdiff_t>(i));
        changed = true;
      }
    }
  }
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
