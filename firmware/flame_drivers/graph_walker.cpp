#include "flame_drivers/graph_walker.h"

#include <algorithm>

namespace candela {
namespace {
constexpr Fixed kOne = Fixed::from_int(1);

// How well a frame's lean matches the target: 1 / (1 + (miss / tolerance)^2).
Fixed lean_match(Fixed lean, Fixed target, Fixed tolerance) {
  Fixed m = abs(lean - target) / tolerance;
  m = std::min(m, Fixed::from_int(150));  // m^2 stays inside Q16.16
  return kOne / (kOne + m * m);
}
}  // namespace

GraphWalker::GraphWalker(const model::MotionGraph& graph, std::span<const float> weights,
                         int stride, std::vector<Fixed> lean, const WalkSettings& settings,
                         uint64_t seed)
    : graph_(graph),
      weights_(weights),
      stride_(stride),
      lean_(std::move(lean)),
      s_(settings),
      rng_(seed, 0x6e61),
      guard_(settings.max_stretch, settings.window) {
  const int f = frames();
  lean_.resize(static_cast<size_t>(f));
  if (s_.lean_tolerance.raw <= 0) s_.lean_tolerance = Fixed::from_raw(1);
  // Jump preference: cheaper (closer) jumps are likelier; 1 / (1 + cost / median).
  std::vector<float> sorted(graph_.cost.begin(), graph_.cost.end());
  std::sort(sorted.begin(), sorted.end());
  const float median = sorted.empty() ? 1.0f : std::max(1e-6f, sorted[sorted.size() / 2]);
  inv_cost_.resize(graph_.cost.size());
  // At least one raw unit: a jump ~1e5x the median cost would round to 0, and a
  // frame whose jumps all did would divide by a zero sum in step().
  for (size_t i = 0; i < graph_.cost.size(); ++i)
    inv_cost_[i] =
        std::max(Fixed::from_raw(1),
                 Fixed::from_double(1.0 / (1.0 + std::max(0.0f, graph_.cost[i]) / median)));
  // Lean bins.
  Fixed lo = Fixed::from_int(1000), hi = Fixed::from_int(-1000);
  for (Fixed l : lean_) lo = std::min(lo, l), hi = std::max(hi, l);
  if (f == 0) lo = hi = Fixed{};
  lean_lo_ = lo;
  lean_step_ = Fixed::from_raw(std::max<int32_t>(1, (hi - lo).raw / kLeanBins + 1));
  bin_offsets_.assign(kLeanBins + 1, 0);
  for (Fixed l : lean_) ++bin_offsets_[static_cast<size_t>(bin_of(l)) + 1];
  for (int b = 0; b < kLeanBins; ++b) bin_offsets_[b + 1] += bin_offsets_[b];
  bin_frames_.resize(static_cast<size_t>(f));
  std::vector<int32_t> fill(bin_offsets_.begin(), bin_offsets_.end() - 1);
  for (int32_t i = 0; i < f; ++i) bin_frames_[static_cast<size_t>(fill[bin_of(lean_[i])]++)] = i;
  current_ = f > 0 ? static_cast<int32_t>(rng_.below(static_cast<uint32_t>(f))) : 0;
  shown_at_.assign(static_cast<size_t>(f), kNeverShown);
  // A model of a few frames must still be able to move.
  revisit_ = static_cast<uint64_t>(std::min(s_.max_stretch, f / 2));
  dead_end_.assign(static_cast<size_t>(f), 1);
  for (int32_t i = 0; i < f; ++i)
    for (int32_t k = graph_.offsets[i]; k < graph_.offsets[i + 1]; ++k)
      if (is_natural(i, graph_.successors[k])) dead_end_[static_cast<size_t>(i)] = 0;
  show(current_);
}

bool GraphWalker::allows(int32_t from, int32_t frame) const {
  // Out of a dead end only to a frame last shown over L steps ago: the jump
  // there is forced, so a short way back would be taken every time round.
  // (Elsewhere a jump back is a 1-in-12 chance per frame: no loop forms, and
  // the wind's steering keeps all its frames.)
  const uint64_t at = shown_at_[static_cast<size_t>(frame)];
  return (!dead_end_[static_cast<size_t>(from)] || at == kNeverShown || steps_ - at > revisit_) &&
         guard_.allows(frame);
}

void GraphWalker::show(int32_t frame) {
  guard_.push(frame);
  shown_at_[static_cast<size_t>(frame)] = ++steps_;
}

int GraphWalker::bin_of(Fixed lean) const {
  const int b = (lean - lean_lo_).raw / lean_step_.raw;
  return std::clamp(b, 0, kLeanBins - 1);
}

int32_t GraphWalker::steer_candidate(Fixed target) {
  // A random frame from the target's bin, or the nearest bin that has frames.
  const int home = bin_of(target);
  for (int d = 0; d < kLeanBins; ++d)
    for (int b : {home - d, home + d}) {
      if (b < 0 || b >= kLeanBins) continue;
      const int32_t n = bin_offsets_[b + 1] - bin_offsets_[b];
      if (n > 0) return bin_frames_[bin_offsets_[b] + rng_.below(static_cast<uint32_t>(n))];
    }
  return current_;
}

float GraphWalker::distance2(int32_t a, int32_t b) const {
  // Fixed order, no contraction (-ffp-contract=off): the same on every machine.
  const float* wa = weights_.data() + static_cast<size_t>(a) * stride_;
  const float* wb = weights_.data() + static_cast<size_t>(b) * stride_;
  float d = 0.0f;
  for (int k = 0; k < std::min(stride_, kBridgeComponents); ++k) {
    const float x = wa[k] - wb[k];
    d = d + x * x;
  }
  return d;
}

int32_t GraphWalker::bridge(int32_t toward, Fixed target, bool steer_only) {
  // Among seeded samples (some from the wind's lean bin, the rest anywhere),
  // the allowed frame nearest to `toward`, penalised for leaning wrong.
  const uint32_t f = static_cast<uint32_t>(frames());
  int32_t best = -1;
  float best_score = 0;
  for (int i = 0; i < kBridgeSamples; ++i) {
    const int32_t c = steer_only || i < kBridgeSamples / 4 ? steer_candidate(target)
                                                           : static_cast<int32_t>(rng_.below(f));
    if (c == toward || !allows(current_, c)) continue;
    const float miss = (abs(lean_[c] - target) / s_.lean_tolerance).to_float();
    const float score = distance2(toward, c) * (1.0f + miss * miss);
    if (best < 0 || score < best_score) best = c, best_score = score;
  }
  return best;
}

int32_t GraphWalker::step(Fixed target) {
  const int32_t from = current_;
  const int32_t begin = graph_.offsets[from], end = graph_.offsets[from + 1];
  bool has_natural = false;
  Fixed jump_pref_sum;
  for (int32_t i = begin; i < end; ++i) {
    if (is_natural(from, graph_.successors[i]))
      has_natural = true;
    else
      jump_pref_sum += inv_cost_[i];
  }
  // Each candidate's weight: its share of the walk's habits times its lean match.
  auto weight = [&](int32_t i) -> Fixed {
    const int32_t to = graph_.successors[i];
    Fixed w;
    if (is_natural(from, to))
      w = jump_pref_sum.raw > 0 ? kOne - s_.jump_chance : kOne;
    else  // jump_pref_sum >= inv_cost_[i] > 0 here (inv_cost_ is never 0)
      w = (has_natural ? s_.jump_chance : kOne) * inv_cost_[i] / jump_pref_sum;
    return w * lean_match(lean_[to], target, s_.lean_tolerance);
  };
  Fixed total;
  Fixed best_miss = Fixed::from_int(1000);
  for (int32_t i = begin; i < end; ++i) {
    const int32_t to = graph_.successors[i];
    if (!allows(from, to)) continue;
    total += std::max(weight(i), Fixed::from_raw(1));
    best_miss = std::min(best_miss, abs(lean_[to] - target));
  }
  int32_t next = -1;
  // Steering: nothing reachable leans as the wind asks; now and then jump to a frame that does.
  if (best_miss > s_.lean_tolerance * 2 && rng_.unit() < s_.steer_chance) {
    const int32_t c = bridge(graph_.successors[begin], target, true);
    if (c >= 0 && abs(lean_[c] - target) < best_miss) {
      next = c;
      ++steers_;
    }
  }
  if (next < 0 && total.raw > 0) {
    int32_t pick = static_cast<int32_t>(rng_.below(static_cast<uint32_t>(total.raw)));
    for (int32_t i = begin; i < end && next < 0; ++i) {
      const int32_t to = graph_.successors[i];
      if (!allows(from, to)) continue;
      pick -= std::max(weight(i), Fixed::from_raw(1)).raw;
      if (pick < 0) next = to;
    }
  }
  if (next < 0) {
    // Every successor would replay a stretch: leave for a frame that does not.
    ++refusals_;
    next = bridge(graph_.successors[begin], target, false);
    const int32_t f = frames();
    for (int32_t k = 0, start = static_cast<int32_t>(rng_.below(static_cast<uint32_t>(f)));
         k < f && next < 0; ++k)
      if (allows(from, (start + k) % f)) next = (start + k) % f;
    if (next < 0) next = graph_.successors[begin];  // only if every frame repeats (tiny models)
  }
  if (!is_natural(from, next)) ++jumps_;
  show(next);
  current_ = next;
  return next;
}

float fade(Fixed phase, Fixed crossfade) {
  // Hold the frame, then fade into the next over the last `crossfade` of the interval.
  if (crossfade.raw <= 0) return 0.0f;
  const float start = 1.0f - crossfade.to_float();
  return std::clamp((phase.to_float() - start) / crossfade.to_float(), 0.0f, 1.0f);
}

GraphPlayer::GraphPlayer(GraphWalker walker, std::span<const float> weights, int components,
                         Fixed frames_per_step)
    : walker_(std::move(walker)),
      weights_(weights),
      e_(std::min(components, kMaxComponents)),
      stride_(components),
      per_step_(frames_per_step) {
  ring_[0] = ring_[1] = walker_.current();
  ring_[2] = walker_.step(target_);
  ring_[3] = walker_.step(target_);
  refresh();
  out_ = a_;
}

void GraphPlayer::blended(int at, float* out) const {
  const int32_t prev = ring_[at - 1], f = ring_[at], next = ring_[at + 1];
  const float* w = weights_.data() + static_cast<size_t>(f) * stride_;
  for (int k = 0; k < e_; ++k) out[k] = w[k];
  if (f == prev + 1 && next == f + 1) return;
  const float* wp = weights_.data() + static_cast<size_t>(prev) * stride_;
  const float* wn = weights_.data() + static_cast<size_t>(next) * stride_;
  const int n = std::min(e_, GraphWalker::kBlendComponents);
  for (int k = 0; k < n; ++k) out[k] = (wp[k] + w[k] + wn[k]) * (1.0f / 3.0f);
}

void GraphPlayer::refresh() {
  blended(1, a_.data());
  blended(2, b_.data());
}

void GraphPlayer::step(Fixed target_lean) {
  target_ = target_lean;
  phase_ += per_step_;
  bool moved = false;
  while (phase_ >= kOne) {
    phase_ -= kOne;
    ring_[0] = ring_[1];
    ring_[1] = ring_[2];
    ring_[2] = ring_[3];
    ring_[3] = walker_.step(target_);
    moved = true;
  }
  if (moved) refresh();
  const float t = fade(phase_, crossfade_);
  for (int k = 0; k < e_; ++k) out_[k] = a_[k] + (b_[k] - a_[k]) * t;
}

}  // namespace candela
