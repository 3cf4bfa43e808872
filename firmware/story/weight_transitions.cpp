#include "story/weight_transitions.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <unordered_set>

namespace candela::story {

WeightTable::WeightTable(std::span<const float> weights, int stride, int frames,
                         const std::vector<model::ClipInfo>& clips, int dims)
    : w_(weights),
      stride_(stride),
      dims_(dims > 0 && dims < stride ? dims : stride),
      frames_(frames) {
  clip_of_.assign(static_cast<size_t>(frames), 0);
  for (size_t c = 0; c < clips.size(); ++c) {
    clip_first_.push_back(clips[c].first);
    clip_end_.push_back(clips[c].first + clips[c].count);
    for (int f = clips[c].first; f < clips[c].first + clips[c].count && f < frames; ++f)
      clip_of_[static_cast<size_t>(f)] = static_cast<int>(c);
  }
  if (clips.empty()) {
    clip_first_.push_back(0);
    clip_end_.push_back(frames);
  }
}

WeightTable WeightTable::of(const model::FlameModel& m, int dims) {
  return WeightTable(m.weights, m.components(), m.frames(), m.clips, dims);
}

float WeightTable::distance(const float* a, const float* b) const {
  charge(static_cast<uint64_t>(dims_));
  double d = 0;
  for (int k = 0; k < dims_; ++k) {
    const double x = static_cast<double>(a[k]) - b[k];
    d = d + x * x;
  }
  return static_cast<float>(std::sqrt(d));
}

float WeightTable::median_step() const {
  std::vector<float> steps;
  for (int i = 0; i + 1 < frames_; ++i)
    if (clip_of(i) == clip_of(i + 1)) steps.push_back(distance(i, i + 1));
  if (steps.empty()) return 1.0f;
  std::nth_element(steps.begin(), steps.begin() + static_cast<ptrdiff_t>(steps.size() / 2),
                   steps.end());
  return std::max(steps[steps.size() / 2], 1e-6f);
}

float WeightTable::step_quantile_ratio(double q) const {
  std::vector<float> steps;
  for (int i = 0; i + 1 < frames_; ++i)
    if (clip_of(i) == clip_of(i + 1)) steps.push_back(distance(i, i + 1));
  if (steps.empty()) return 1.0f;
  std::sort(steps.begin(), steps.end());
  const size_t at =
      std::min(steps.size() - 1, static_cast<size_t>(q * static_cast<double>(steps.size())));
  return steps[at] / median_step();
}

namespace {

std::vector<uint8_t> initial_rejections(const WeightTable& s, int alpha, int beta, int tail) {
  std::vector<uint8_t> used(static_cast<size_t>(s.frames()), 0);
  used[alpha] = used[beta] = 1;
  for (int i = 1; i <= tail; ++i) {
    if (alpha - i >= s.clip_first(s.clip_of(alpha))) used[alpha - i] = 1;
    if (beta + i < s.clip_end(s.clip_of(beta))) used[beta + i] = 1;
  }
  return used;
}

void check_ends(const WeightTable& s, int alpha, int beta) {
  if (alpha < 0 || beta < 0 || alpha >= s.frames() || beta >= s.frames())
    throw std::out_of_range("transition ends must be frames of the model");
}

}  // namespace

FramePath direct_bridging(const WeightTable& s, int alpha, int beta, const PathOptions& o) {
  check_ends(s, alpha, beta);
  FramePath t;
  std::vector<uint8_t> used = initial_rejections(s, alpha, beta, o.reject_tail);
  t.path.push_back(alpha);
  const int e = s.dims();
  std::vector<float> target(static_cast<size_t>(s.stride()));
  const float* a = s.row(alpha);
  const float* b = s.row(beta);
  for (int i = 1; i <= o.steps; ++i) {
    const float u = static_cast<float>(i) / static_cast<float>(o.steps + 1);
    for (int k = 0; k < e; ++k) target[k] = a[k] + (b[k] - a[k]) * u;
    int best = -1;
    float best_d = 0;
    for (int f = 0; f < s.frames(); ++f) {
      if (used[f] || s.distance(t.path.back(), f) < o.theta_min) continue;
      const float d = s.distance(s.row(f), target.data());
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

FramePath end_growing(const WeightTable& s, int alpha, int beta, const PathOptions& o) {
  check_ends(s, alpha, beta);
  FramePath t;
  const float theta = o.theta_min;
  std::vector<uint8_t> used = initial_rejections(s, alpha, beta, o.reject_tail);
  std::vector<int> from_a{alpha}, from_b{beta};
  std::vector<int> sa, sb;
  std::vector<float> da(static_cast<size_t>(s.frames())), db(static_cast<size_t>(s.frames()));
  auto join = [&](int shared) {
    t.path = from_a;
    if (shared >= 0) t.path.push_back(shared);
    t.path.insert(t.path.end(), from_b.rbegin(), from_b.rend());
    t.found = true;
  };
  auto unjoined = [&] {
    t.path = from_a;
    t.path.insert(t.path.end(), from_b.rbegin(), from_b.rend());
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
      da[f] = s.distance(a, f);
      db[f] = s.distance(b, f);
      if (da[f] >= theta && da[f] < D) sa.push_back(f);
      if (db[f] >= theta && db[f] < D) sb.push_back(f);
    }
    auto by_a = [&](int x, int y) { return da[x] < da[y] || (da[x] == da[y] && x < y); };
    auto by_b = [&](int x, int y) { return db[x] < db[y] || (db[x] == db[y] && x < y); };
    std::sort(sa.begin(), sa.end(), by_a);
    std::sort(sb.begin(), sb.end(), by_b);
    // Table 1: walk both sorted lists; a frame near both ends joins them.
    std::unordered_set<int> seen_a, seen_b;
    size_t j = 0, k = 0;
    bool found_step = false;
    while (j < sa.size() && k < sb.size() && !found_step) {
      const int aj = sa[j], bk = sb[k];
      seen_a.insert(aj);
      seen_b.insert(bk);
      const int shared = aj == bk || seen_b.count(aj) ? aj : (seen_a.count(bk) ? bk : -1);
      if (shared >= 0) {
        t.how = "shared image";
        join(shared);
        optimise_path(s, t.path, theta);
        return t;
      }
      const float d12 = s.distance(aj, bk), d1 = db[aj], d2 = da[bk];
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
      unjoined();
      return t;
    }
  }
  if (s.distance(from_a.back(), from_b.back()) < theta) {
    t.how = "gap below theta_min";
    join(-1);
    optimise_path(s, t.path, theta);
    return t;
  }
  t.how = "not connected within " + std::to_string(o.steps) + " steps";
  unjoined();
  return t;
}

void optimise_path(const WeightTable& s, std::vector<int>& path, float theta_min) {
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

std::vector<float> lowpass_rows(const WeightTable& s, std::span<const int> t1,
                                std::span<const int> t2, std::array<float, 3> kernel,
                                int filtered) {
  if (t1.size() < 2 || t2.size() < 2)
    throw std::invalid_argument("low-pass transition needs two frames on each side");
  // The joined sequence: up to three frames of T1, then up to three of T2.
  std::vector<int> seq(t1.end() - std::min<ptrdiff_t>(3, static_cast<ptrdiff_t>(t1.size())),
                       t1.end());
  const int n1 = static_cast<int>(seq.size());
  seq.insert(seq.end(), t2.begin(),
             t2.begin() + std::min<ptrdiff_t>(3, static_cast<ptrdiff_t>(t2.size())));
  const int e = s.stride(), f = std::min(filtered, e);
  std::vector<float> out(static_cast<size_t>(4) * e);
  for (int r = 0; r < 4; ++r) {
    const int i = n1 - 2 + r;
    float* o = out.data() + static_cast<size_t>(r) * e;
    std::copy(s.row(seq[i]), s.row(seq[i]) + e, o);
    for (int c = 0; c < f; ++c) {
      float acc = 0;
      for (int j = 0; j < 3; ++j) {
        const float k = r < 2 ? kernel[j] : kernel[2 - j];
        const int at = std::clamp(i + j - 1, 0, static_cast<int>(seq.size()) - 1);
        acc = acc + k * s.row(seq[at])[c];
      }
      o[c] = acc;
    }
  }
  return out;
}

}  // namespace candela::story
