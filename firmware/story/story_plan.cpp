#include "story/story_plan.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <unordered_set>

#include "core/error.h"
#include "core/fixed.h"
#include "core/random.h"
#include "flame_drivers/arp_driver.h"
#include "flame_drivers/graph_walker.h"

namespace candela::story {
namespace {

[[noreturn]] void fail(const StoryDesc& s, const std::string& key, const std::string& problem) {
  throw ConfigError(s.file, key, problem);
}

int frames_for(const StoryDesc& s, const SegmentSpec& g, double fps, const char* what) {
  const double n = std::round(g.seconds * fps);
  if (n > kMaxStoryFrames)
    fail(s, g.key + "." + what,
         "expected at most " + std::to_string(kMaxStoryFrames) + " frames (" +
             std::to_string(g.seconds) + " s at the model's " + std::to_string(fps) + " fps)");
  if (n < kMinSegmentFrames)
    fail(s, g.key + "." + what,
         "expected at least " + std::to_string(kMinSegmentFrames) + " frames at the model's " +
             std::to_string(fps) + " fps");
  return static_cast<int>(n);
}

std::vector<int> clip_frames(const StoryDesc& s, const SegmentSpec& g, const model::FlameModel& m) {
  int first = 0, count = m.frames();
  if (!g.clip.empty()) {
    auto it = std::find_if(m.clips.begin(), m.clips.end(),
                           [&](const model::ClipInfo& c) { return c.name == g.clip; });
    if (it == m.clips.end()) {
      std::string names;
      for (const auto& c : m.clips) names += (names.empty() ? "\"" : ", \"") + c.name + "\"";
      fail(s, g.key + ".clip",
           "expected a clip of the model (" + names + "), got \"" + g.clip + "\"");
    }
    first = it->first;
    count = it->count;
  }
  const std::string where = g.clip.empty()
                                ? "the model's " + std::to_string(count) + " frames"
                                : "clip \"" + g.clip + "\" (" + std::to_string(count) + " frames)";
  const int to = g.to < 0 ? count : g.to;
  if (to > count)
    fail(s, g.key + ".to", "expected at most " + std::to_string(count) + ": " + where);
  if (to - g.from < kMinSegmentFrames)
    fail(s, g.key + ".from",
         "expected at least " + std::to_string(kMinSegmentFrames) + " frames before the end of " +
             where + ", got from = " + std::to_string(g.from));
  std::vector<int> out;
  for (int f = first + g.from; f < first + to; ++f) out.push_back(f);
  return out;
}

std::vector<int> walk_frames(const SegmentSpec& g, int n, const model::FlameModel& m,
                             uint64_t seed) {
  (void)g;
  // No wind steers a planned walk: every frame leans alike.
  GraphWalker walker(m.graph, m.weights, m.components(),
                     std::vector<Fixed>(static_cast<size_t>(m.frames())), WalkSettings{}, seed);
  std::vector<int> out{walker.current()};
  while (static_cast<int>(out.size()) < n) out.push_back(walker.step(Fixed{}));
  return out;
}

// Learning Flames trains on the frames with one plume: the model's frames
// minus info "multi_plume", in order (tools/model/learning_flames.cpp).
std::vector<int> training_frames(const StoryDesc& s, const SegmentSpec& g,
                                 const model::FlameModel& m) {
  std::unordered_set<int> skipped;
  const auto& info = m.file().info();
  if (info.contains("multi_plume") && info["multi_plume"].is_array())
    for (const auto& v : info["multi_plume"])
      if (v.is_number_integer()) skipped.insert(v.get<int>());
  std::vector<int> out;
  for (int f = 0; f < m.frames(); ++f)
    if (!skipped.count(f)) out.push_back(f);
  if (static_cast<int>(out.size()) != m.flames.frames)
    fail(s, g.key + ".arp",
         "expected a model whose Learning Flames frames match its frames (" +
             std::to_string(m.flames.frames) + " training states, " + std::to_string(out.size()) +
             " single-plume frames)");
  return out;
}

// ARP synthesis in weight space: each synthesised state shows one of the
// kArpCandidates model frames whose training states are nearest to it (each
// parameter scaled by its training standard deviation): the one a step
// nearest to the frame shown before, so the whole story plays through
// EigenFires and the synthesis does not flicker between look-alikes.
constexpr int kArpCandidates = 6;

std::vector<int> arp_frames(const StoryDesc& s, const SegmentSpec& g, int n,
                            const model::FlameModel& m, const WeightTable& table, uint64_t seed) {
  if (!m.has_learning_flames)
    fail(s, g.key + ".arp",
         "expected a model with a Learning Flames part (this one has none; use walk = SECONDS)");
  const std::vector<int> frame_of = training_frames(s, g, m);
  const ArpView view = ArpView::of(m.flames);
  const int d = view.dim, t = view.frames();
  std::vector<double> inv_std(static_cast<size_t>(d));
  for (int i = 0; i < d; ++i) {
    double sum = 0, sq = 0;
    for (int f = 0; f < t; ++f) {
      const double x = view.training[static_cast<size_t>(f) * d + i];
      sum += x;
      sq += x * x;
    }
    const double mean = sum / t, var = std::max(0.0, sq / t - mean * mean);
    inv_std[static_cast<size_t>(i)] = var > 1e-12 ? 1.0 / std::sqrt(var) : 0.0;
  }
  ArpProcess arp(view, seed);
  std::vector<int> out;
  std::vector<std::pair<double, int>> near(static_cast<size_t>(t));
  auto show = [&](std::span<const float> x) {
    table.charge(static_cast<uint64_t>(t) * static_cast<uint64_t>(d));
    for (int f = 0; f < t; ++f) {
      double dd = 0;
      for (int i = 0; i < d; ++i) {
        const double v = (x[i] - view.training[static_cast<size_t>(f) * d + i]) * inv_std[i];
        dd = dd + v * v;
      }
      near[static_cast<size_t>(f)] = {dd, f};
    }
    const size_t k = std::min<size_t>(kArpCandidates, near.size());
    std::partial_sort(near.begin(), near.begin() + static_cast<ptrdiff_t>(k), near.end());
    int best = frame_of[static_cast<size_t>(near[0].second)];
    if (!out.empty()) {
      float best_step = table.distance(out.back(), best);
      for (size_t c = 1; c < k; ++c) {
        const int f = frame_of[static_cast<size_t>(near[c].second)];
        const float step = table.distance(out.back(), f);
        if (f != out.back() && (best == out.back() || step < best_step)) best = f, best_step = step;
      }
    }
    out.push_back(best);
  };
  show(arp.state());
  while (static_cast<int>(out.size()) < n) show(arp.step());
  return out;
}

// A joint whose ends are at most this many median steps apart is joined as
// it is (grow and an automatic bridge would insert nothing useful).
constexpr float kNearRatio = 1.5f;

struct Piece {
  int segment = 0, repeat = 0;
  const std::vector<int>* frames = nullptr;
};

}  // namespace

const float* StoryPlan::weights_of(int i) const {
  const int n = frames();
  i = ((i % n) + n) % n;
  const int32_t r = ref_[static_cast<size_t>(i)];
  if (r >= 0) return model_weights_.data() + static_cast<size_t>(r) * stride_;
  return rows_.data() + static_cast<size_t>(-1 - r) * stride_;
}

int StoryPlan::model_frame(int i) const {
  const int n = frames();
  const int32_t r = ref_[static_cast<size_t>(((i % n) + n) % n)];
  return r >= 0 ? r : -1;
}

float StoryPlan::step_ratio(int i) const {
  const float* a = weights_of(i);
  const float* b = weights_of(i + 1);
  double d = 0;
  for (int k = 0; k < dims_; ++k) {
    const double x = static_cast<double>(a[k]) - b[k];
    d = d + x * x;
  }
  return static_cast<float>(std::sqrt(d)) / median_;
}

float StoryPlan::worst_seam() const {
  float w = 0;
  for (const auto& j : joints_) w = std::max(w, j.seam_ratio);
  return w;
}

StoryPlan plan_story(const StoryDesc& story, const model::FlameModel& m, uint64_t seed,
                     bool force_loop) {
  StoryPlan plan;
  // What was being planned when the work limit was reached (for its message).
  std::string working_on = "segment";
  try {
    WeightTable table = WeightTable::of(m, story.components);
    table.set_work_limit(kMaxPlanWork);
    plan.model_weights_ = m.weights;
    plan.stride_ = m.components();
    plan.dims_ = table.dims();
    plan.fps_ = m.clips.empty() ? 30.0 : m.clips.front().fps;
    plan.loop_ = story.loop || force_loop;
    plan.median_ = table.median_step();
    plan.bound_ = std::max(kMinSeamBound, table.step_quantile_ratio(kSeamQuantile));

    // Each segment's frames, once (its repeats replay them).
    std::vector<std::vector<int>> seg_frames;
    int64_t total = 0;
    for (size_t i = 0; i < story.segments.size(); ++i) {
      const SegmentSpec& g = story.segments[i];
      working_on = g.key;
      const uint64_t sseed = split_seed(seed, i);
      switch (g.kind) {
        case SegmentKind::kFrames:
          seg_frames.push_back(clip_frames(story, g, m));
          break;
        case SegmentKind::kWalk:
          seg_frames.push_back(walk_frames(g, frames_for(story, g, plan.fps_, "walk"), m, sseed));
          break;
        case SegmentKind::kArp:
          seg_frames.push_back(
              arp_frames(story, g, frames_for(story, g, plan.fps_, "arp"), m, table, sseed));
          break;
      }
      total += static_cast<int64_t>(seg_frames.back().size()) * g.repeat;
      if (total > kMaxStoryFrames)
        fail(story, g.key,
             "expected a story of at most " + std::to_string(kMaxStoryFrames) +
                 " frames; it reaches " + std::to_string(total) + " here (with repeats)");
    }
    std::vector<Piece> pieces;
    for (size_t i = 0; i < story.segments.size(); ++i)
      for (int r = 0; r < story.segments[i].repeat; ++r)
        pieces.push_back({static_cast<int>(i), r, &seg_frames[i]});

    std::vector<int32_t>& ref = plan.ref_;
    std::vector<float>& rows = plan.rows_;
    const int e = plan.stride_;
    auto add_row = [&](const float* w) {
      rows.insert(rows.end(), w, w + e);
      return static_cast<int32_t>(-static_cast<int64_t>(rows.size() / e));
    };
    // What a joint puts between two pieces depends only on the two segments
    // (their frames and the entered segment's transition), so it is worked out
    // once for each pair of segments that meet and replayed at every repeat:
    // repeats do not multiply the planning work.
    struct JointWork {
      JointReport report;         // what, first and last are filled in where it is used
      std::vector<int> inserted;  // model frames between alpha and beta
      bool lowpass = false;
      std::array<int32_t, 4> rows{};  // low-pass: T1's last two and T2's first two, rewritten
    };
    std::map<std::pair<int, int>, JointWork> worked;
    auto work_out = [&](int prev_segment, int next_segment) -> const JointWork& {
      auto found = worked.find({prev_segment, next_segment});
      if (found != worked.end()) return found->second;
      JointWork& w = worked[{prev_segment, next_segment}];
      const SegmentSpec& g = story.segments[static_cast<size_t>(next_segment)];
      const TransitionSpec& t = g.transition;
      working_on = t.key;
      const std::vector<int>& a = seg_frames[static_cast<size_t>(prev_segment)];
      const std::vector<int>& b = seg_frames[static_cast<size_t>(next_segment)];
      JointReport& j = w.report;
      j.key = t.key;
      j.method = t.method;
      j.alpha = a.back();
      j.beta = b.front();
      j.cut_ratio = table.distance(j.alpha, j.beta) / plan.median_;
      const float theta = t.theta_min > 0 ? t.theta_min : 0.5f * plan.median_;
      // A path in, unless it is rougher than the cut it would replace.
      auto insert = [&](const std::vector<int>& path) {
        float worst = 0;
        for (size_t k = 0; k + 1 < path.size(); ++k)
          worst = std::max(worst, table.distance(path[k], path[k + 1]) / plan.median_);
        if (path.size() > 2 && worst > j.cut_ratio) {
          char why[96];
          std::snprintf(why, sizeof why,
                        "; its largest step %.2f is rougher than a cut: joined directly",
                        static_cast<double>(worst));
          j.how += why;
          return;
        }
        for (size_t k = 1; k + 1 < path.size(); ++k) w.inserted.push_back(path[k]);
      };
      Method how = t.method;
      // Ends already about an ordinary step apart need no frames between them.
      const bool near = j.cut_ratio <= kNearRatio && (how == Method::kGrow || t.steps <= 0);
      if (near && (how == Method::kGrow || how == Method::kBridge)) {
        how = Method::kCut;
        j.how = "ends an ordinary step apart: joined directly";
      }
      if (how == Method::kGrow && j.alpha != j.beta) {
        PathOptions o{t.steps, theta, t.reject_tail};
        FramePath p = end_growing(table, j.alpha, j.beta, o);
        if (!p.found && o.steps < kMaxTransitionSteps) {
          // Far ends: give the growth room before settling for a bridge.
          o.steps = kMaxTransitionSteps;
          p = end_growing(table, j.alpha, j.beta, o);
          if (p.found) p.how += " (grown with steps = " + std::to_string(o.steps) + ")";
        }
        if (p.found) {
          j.how = p.how;
          insert(p.path);
        } else {
          j.how = "grow: " + p.how + "; bridged instead";
          how = Method::kBridge;
        }
      }
      if (how == Method::kBridge && j.alpha != j.beta) {
        int steps = t.steps;
        if (t.method != Method::kBridge || steps <= 0)  // auto: points an ordinary step apart
          steps =
              std::clamp(static_cast<int>(std::lround(j.cut_ratio)) - 1, 0, kMaxTransitionSteps);
        FramePath p = direct_bridging(table, j.alpha, j.beta, {steps, theta, t.reject_tail});
        if (j.how.empty()) j.how = "bridged, N = " + std::to_string(steps);
        insert(p.path);
      }
      j.inserted = static_cast<int>(w.inserted.size());
      if (how == Method::kCut && j.how.empty()) j.how = "hard cut";
      if (how == Method::kLowpass) {
        const std::vector<float> rw = lowpass_rows(
            table, std::span<const int>(a).last(std::min<size_t>(3, a.size())),
            std::span<const int>(b).first(std::min<size_t>(3, b.size())), t.kernel, t.components);
        w.lowpass = true;
        for (size_t r = 0; r < 4; ++r) w.rows[r] = add_row(rw.data() + r * static_cast<size_t>(e));
        j.how = "low-pass over " + std::to_string(std::min(t.components, e)) + " components";
      }
      if (j.alpha == j.beta) j.how = "same frame";
      return w;
    };
    // A joint from `prev` (whose last frame is at story index `alpha_at`) into
    // `next`: appends what goes between them and returns the report (first and
    // last filled in relative to the story as built so far) and, for a
    // low-pass, the rows of `next`'s first two frames.
    auto join = [&](const Piece& prev, const Piece& next,
                    bool loop) -> std::pair<JointReport, const int32_t*> {
      const JointWork& w = work_out(prev.segment, next.segment);
      JointReport j = w.report;
      const SegmentSpec& g = story.segments[static_cast<size_t>(next.segment)];
      const std::string from = story.segments[static_cast<size_t>(prev.segment)].key;
      j.what = loop                           ? "loop: " + from + " -> " + g.key
               : prev.segment == next.segment ? g.key + " repeat " + std::to_string(next.repeat + 1)
                                              : from + " -> " + g.key;
      const int alpha_at = static_cast<int>(ref.size()) - 1;
      j.first = alpha_at;
      ref.insert(ref.end(), w.inserted.begin(), w.inserted.end());
      if (!w.lowpass) return {j, nullptr};
      // T1's last two frames now; T2's first two once they are in place.
      ref[static_cast<size_t>(alpha_at - 1)] = w.rows[0];
      ref[static_cast<size_t>(alpha_at)] = w.rows[1];
      j.first = alpha_at - 2;
      return {j, w.rows.data() + 2};
    };

    for (size_t k = 0; k < pieces.size(); ++k) {
      const int32_t* lowpass_next = nullptr;
      JointReport j;
      const bool joined = k > 0;
      if (joined) std::tie(j, lowpass_next) = join(pieces[k - 1], pieces[k], false);
      const int begin = static_cast<int>(ref.size());
      for (int f : *pieces[k].frames) ref.push_back(f);
      if (lowpass_next) {
        ref[static_cast<size_t>(begin)] = lowpass_next[0];
        ref[static_cast<size_t>(begin + 1)] = lowpass_next[1];
      }
      if (joined) {
        j.last = begin + (lowpass_next ? 2 : 0);
        plan.joints_.push_back(std::move(j));
      }
      PieceReport pr;
      const SegmentSpec& g = story.segments[static_cast<size_t>(pieces[k].segment)];
      pr.key = g.key + (g.repeat > 1 ? " repeat " + std::to_string(pieces[k].repeat + 1) : "");
      pr.first = begin;
      pr.count = static_cast<int>(pieces[k].frames->size());
      const std::vector<int>& fr = *pieces[k].frames;
      for (size_t i = 0; i + 1 < fr.size(); ++i)
        pr.max_step_ratio =
            std::max(pr.max_step_ratio, table.distance(fr[i], fr[i + 1]) / plan.median_);
      plan.pieces_.push_back(pr);
    }
    if (plan.loop_) {
      auto [j, lowpass_next] = join(pieces.back(), pieces.front(), true);
      const int n = static_cast<int>(ref.size());
      if (lowpass_next) {
        ref[0] = lowpass_next[0];
        ref[1] = lowpass_next[1];
      }
      j.last = n + (lowpass_next ? 2 : 0);
      plan.joints_.push_back(std::move(j));
    }
    if (plan.frames() > kMaxStoryFrames)
      fail(story, "segment",
           "expected a story of at most " + std::to_string(kMaxStoryFrames) + " frames, got " +
               std::to_string(plan.frames()) + " with its transitions");
    for (JointReport& j : plan.joints_)
      for (int i = j.first; i < j.last; ++i)
        j.seam_ratio = std::max(j.seam_ratio, plan.step_ratio(i));
    plan.work_ = table.work();
  } catch (const WeightTable::WorkLimitReached&) {
    fail(story, working_on,
         "expected a story that plans within " + std::to_string(kMaxPlanWork / 1000000) +
             " million component operations (about a second of one CPU core); planning "
             "passed that here: use fewer segments, shorter walk or arp segments, fewer transition "
             "steps, fewer components or a model with fewer frames");
  }
  return plan;
}

}  // namespace candela::story
