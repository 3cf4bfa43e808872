// The `graph` driver (EigenFires): an endless random walk over a model's
// motion graph. From each frame the walk takes the next frame of its clip or
// one of the graph's jumps (chosen by a seeded Pcg32, cheaper jumps more
// likely), never a step that would replay a stretch longer than L frames
// within W frames (NoRepeatGuard), and is steered by the wind: candidates
// whose lean (intensity-weighted centroid x of the reconstructed frame, in
// image widths) is near the lean the wind asks for are preferred, and when
// no successor leans far enough the walk may jump to a frame that does.
// From a frame with no next frame (a clip's end) it jumps only to a frame it
// has not shown within the last L steps (F/2 for a model of F < 2L frames):
// a clip's tail whose only exits are jumps a few frames back would otherwise
// be circled every fraction of a second, loops shorter than the L the guard
// looks at.
// Where the graph offers no allowed successor (a sparse graph, or the guard
// refusing them all), the walk bridges to the frame nearest in weight space
// to where it would have gone, among a seeded sample, as Direct Bridging does.
//
// All choices are integer/fixed-point, so a seed gives the same frames on
// every machine. Weights for drawing are blended in float (they only go to
// the GPU): around a jump, the first 50 components are low-passed with the
// kernel [1/3, 1/3, 1/3] over the previous, current and next frame, as the
// EigenFires paper does for transitions.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "core/fixed.h"
#include "core/random.h"
#include "flame_drivers/no_repeat_guard.h"
#include "model/flame_model.h"

namespace candela {

struct WalkSettings {
  int max_stretch = 45;                              // L, frames
  int window = 1800;                                 // W, frames
  Fixed jump_chance = Fixed::from_ratio(1, 12);      // per frame, when a jump is available
  Fixed lean_tolerance = Fixed::from_ratio(3, 100);  // image widths: "leans the same"
  Fixed steer_chance = Fixed::from_ratio(1, 6);      // per frame, when nothing near leans right
};

class GraphWalker {
 public:
  static constexpr int kBlendComponents = 50;
  static constexpr int kLeanBins = 16;

  // lean: one per frame (image widths, + = right). Label hints may be folded
  // into it by the caller. Allocates here only.
  // weights: F x stride floats (the model's per-frame weights).
  // graph: the model's own (model/flame_model.h; its spans outlive the walker).
  GraphWalker(const model::MotionGraph& graph, std::span<const float> weights, int stride,
              std::vector<Fixed> lean, const WalkSettings& settings, uint64_t seed);

  // Chooses and returns the next frame. target_lean: where the wind wants the flame.
  int32_t step(Fixed target_lean);
  int32_t current() const { return current_; }
  uint64_t jumps() const { return jumps_; }
  uint64_t steers() const { return steers_; }
  uint64_t refusals() const { return refusals_; }
  Fixed lean(int32_t frame) const { return lean_[static_cast<size_t>(frame)]; }

 private:
  int frames() const { return static_cast<int>(graph_.offsets.size()) - 1; }
  int bin_of(Fixed lean) const;
  // Neither a short loop out of a dead end (to a frame shown within the last
  // L steps) nor a long replay (the guard).
  bool allows(int32_t from, int32_t frame) const;
  void show(int32_t frame);
  int32_t steer_candidate(Fixed target);
  int32_t bridge(int32_t toward, Fixed target, bool steer_only);
  float distance2(int32_t a, int32_t b) const;
  bool is_natural(int32_t from, int32_t to) const { return to == from + 1; }

  static constexpr int kBridgeComponents = 16;
  static constexpr int kBridgeSamples = 32;

  model::MotionGraph graph_;
  std::span<const float> weights_;
  int stride_;
  std::vector<Fixed> lean_;
  WalkSettings s_;
  Pcg32 rng_;
  NoRepeatGuard guard_;
  // Frames sorted into lean bins (CSR), for steering jumps.
  Fixed lean_lo_, lean_step_;
  std::vector<int32_t> bin_offsets_, bin_frames_;
  std::vector<Fixed> inv_cost_;  // per successor: preference of a jump
  static constexpr uint64_t kNeverShown = ~uint64_t{0};
  std::vector<uint64_t> shown_at_;  // per frame: the step it was last shown at
  std::vector<uint8_t> dead_end_;   // per frame: 1 when the graph has no natural next frame
  uint64_t steps_ = 0, revisit_ = 0;
  int32_t current_ = 0;
  uint64_t jumps_ = 0, steers_ = 0, refusals_ = 0;
};

// How far (0..1) a frame `phase` (0..1) into its interval has faded into the
// next, when the last `crossfade` share of each interval is a fade.
float fade(Fixed phase, Fixed crossfade);

// Plays a walk at the model's frame rate on the fixed animation step and
// blends its weights for drawing: keeps the last chosen frames and the next
// two, low-passes across jumps and interpolates between frames.
class GraphPlayer {
 public:
  static constexpr int kMaxComponents = model::kMaxPlayedComponents;

  GraphPlayer(GraphWalker walker, std::span<const float> weights, int components,
              Fixed frames_per_step);
  void set_rate(Fixed frames_per_step) { per_step_ = frames_per_step; }
  // Share of each frame interval spent fading into the next frame (0: hold
  // each frame, 1: blend linearly from one frame to the next).
  void set_crossfade(Fixed share) { crossfade_ = clamp(share, Fixed{}, Fixed::from_int(1)); }
  // One animation step; target_lean as for GraphWalker::step.
  void step(Fixed target_lean);
  // The weights to draw (components() of them).
  std::span<const float> weights() const { return {out_.data(), static_cast<size_t>(e_)}; }
  int32_t shown_frame() const { return ring_[1]; }
  const GraphWalker& walker() const { return walker_; }
  int components() const { return e_; }

 private:
  void blended(int at, float* out) const;  // frame ring_[at], low-passed if near a jump
  void refresh();

  GraphWalker walker_;
  std::span<const float> weights_;
  int e_;           // components used
  int stride_;      // components per frame in `weights_`
  Fixed per_step_;  // model frames per animation step
  Fixed crossfade_ = Fixed::from_int(1);
  Fixed phase_;
  Fixed target_;
  std::array<int32_t, 4> ring_{};  // previous, shown, next, after next
  std::array<float, kMaxComponents> a_{}, b_{}, out_{};
};

}  // namespace candela
