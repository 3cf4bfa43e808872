#include "story/story_player.h"

#include <algorithm>

#include "flame_drivers/graph_walker.h"

namespace candela::story {

StoryPlayer::StoryPlayer(const StoryPlan& plan, int components, Fixed frames_per_step)
    : n_(plan.frames()),
      e_(std::clamp(components, 1, std::min(plan.components(), kMaxComponents))),
      per_step_(frames_per_step) {
  w_.resize(static_cast<size_t>(n_) * e_);
  for (int i = 0; i < n_; ++i)
    std::copy_n(plan.weights_of(i), e_, w_.data() + static_cast<size_t>(i) * e_);
  std::copy_n(row(0), e_, out_.data());
}

void StoryPlayer::step() {
  phase_ += per_step_;
  while (phase_ >= Fixed::from_int(1)) {
    phase_ -= Fixed::from_int(1);
    if (++at_ == n_) {
      at_ = 0;
      ++loops_;
    }
  }
  const float* a = row(at_);
  const float* b = row(at_ + 1 == n_ ? 0 : at_ + 1);
  const float t = fade(phase_, crossfade_);
  for (int k = 0; k < e_; ++k) out_[k] = a[k] + (b[k] - a[k]) * t;
}

}  // namespace candela::story
