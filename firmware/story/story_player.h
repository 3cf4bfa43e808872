// Plays a planned story at the model's frame rate on the fixed animation
// step, as GraphPlayer plays a walk: holds each story frame and fades into
// the next over the last `crossfade` share of its interval, and wraps from
// the last frame to the first (the plan's loop joint lies between them).
// Copies the plan's weights once at construction; step() allocates nothing.
#pragma once

#include <array>
#include <span>
#include <vector>

#include "core/fixed.h"
#include "model/flame_model.h"
#include "story/story_plan.h"

namespace candela::story {

class StoryPlayer {
 public:
  static constexpr int kMaxComponents = model::kMaxPlayedComponents;

  // components: how many to play (at most the plan's and kMaxComponents).
  StoryPlayer(const StoryPlan& plan, int components, Fixed frames_per_step);
  void set_rate(Fixed frames_per_step) { per_step_ = frames_per_step; }
  void set_crossfade(Fixed share) { crossfade_ = clamp(share, Fixed{}, Fixed::from_int(1)); }
  void step();
  std::span<const float> weights() const { return {out_.data(), static_cast<size_t>(e_)}; }
  int frame() const { return at_; }  // the story frame shown (fading into the next)
  int frames() const { return n_; }
  int components() const { return e_; }
  uint64_t loops() const { return loops_; }

 private:
  const float* row(int i) const { return w_.data() + static_cast<size_t>(i) * e_; }
  std::vector<float> w_;  // n_ x e_
  int n_, e_;
  Fixed per_step_;
  Fixed crossfade_ = Fixed::from_ratio(1, 4);
  Fixed phase_;
  int at_ = 0;
  uint64_t loops_ = 0;
  std::array<float, kMaxComponents> out_{};
};

}  // namespace candela::story
