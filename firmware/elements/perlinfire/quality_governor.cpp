#include "elements/perlinfire/quality_governor.h"

#include <algorithm>
#include <utility>

namespace candela {

std::vector<QualityLevel> QualityGovernor::make_ladder(QualityLevel top, int min_steps,
                                                       int min_octaves, float min_scale) {
  std::vector<QualityLevel> ladder{top};
  QualityLevel q = top;
  // Scale first (it divides the pixel count), then steps, then octaves.
  for (int turn = 0;; ++turn) {
    bool lowered = false;
    for (int k = 0; k < 3 && !lowered; ++k) {
      switch ((turn + k) % 3) {
        case 0:
          if (q.scale > min_scale + 1e-4f) {
            q.scale = std::max(min_scale, q.scale * 0.75f);
            lowered = true;
          }
          break;
        case 1:
          if (q.steps > min_steps) {
            q.steps = std::max(min_steps, q.steps * 3 / 4);
            lowered = true;
          }
          break;
        default:
          if (q.octaves > min_octaves) {
            --q.octaves;
            lowered = true;
          }
          break;
      }
    }
    if (!lowered) break;
    ladder.push_back(q);
  }
  return ladder;
}

QualityGovernor::QualityGovernor(std::vector<QualityLevel> ladder, Settings settings)
    : ladder_(std::move(ladder)),
      s_(settings),
      skip_(settings.warmup),
      raise_after_(settings.raise_after) {
  if (ladder_.empty()) ladder_.push_back(QualityLevel{});
  ratio_.assign(ladder_.size(), 0.0);
}

void QualityGovernor::change_to(int level, int warmup) {
  left_level_ = level_;
  left_mean_ = sum_ / std::max(count_, 1);
  level_ = level;
  ++changes_;
  skip_ = warmup;
  count_ = 0;
  sum_ = 0;
  good_windows_ = 0;
}

bool QualityGovernor::add_frame(double frame_ms) {
  if (skip_ > 0) {
    --skip_;
    return false;
  }
  sum_ += frame_ms;
  ++count_;
  const bool far_over = count_ >= s_.quick_window && sum_ > s_.budget_ms * s_.far_above * count_;
  if (count_ < s_.window && !far_over) return false;
  const double mean = sum_ / count_;
  // The first window after a change: learn how the two levels compare.
  if (left_level_ >= 0 && mean > 0) {
    const int lower = std::max(left_level_, level_);
    ratio_[static_cast<size_t>(lower)] =
        left_level_ < level_ ? left_mean_ / mean : mean / left_mean_;
    left_level_ = -1;
  }
  if (mean > s_.budget_ms * s_.lower_above) {
    if (level_ + 1 >= levels()) {
      count_ = 0, sum_ = 0;
      return false;  // already at the floor
    }
    // Falling back right after a raise: that raise was a mistake; wait longer next time.
    if (raised_from_ == level_ + 1) raise_after_ = std::min(raise_after_ * 2, s_.max_raise_after);
    raised_from_ = -1;
    // Twice as far over again: two levels at once (and no ratio learnt from
    // that jump, which spans two).
    const bool very_far = far_over && mean > 2 * s_.far_above * s_.budget_ms;
    change_to(std::min(level_ + (very_far ? 2 : 1), levels() - 1),
              far_over ? s_.quick_warmup : s_.warmup);
    if (very_far) left_level_ = -1;
    return true;
  }
  // A window within budget at a raised level ends its probation.
  if (raised_from_ >= 0) {
    raised_from_ = -1;
    raise_after_ = s_.raise_after;
  }
  const double ratio = level_ > 0 ? ratio_[static_cast<size_t>(level_)] : 0.0;
  const bool fits_above = ratio <= 0 || mean * ratio < s_.budget_ms * s_.predicted_below;
  if (level_ > 0 && mean < s_.budget_ms * s_.raise_below && fits_above) {
    if (++good_windows_ >= raise_after_) {
      raised_from_ = level_;
      change_to(level_ - 1, s_.warmup);
      return true;
    }
  } else {
    good_windows_ = 0;
  }
  count_ = 0;
  sum_ = 0;
  return false;
}

}  // namespace candela
