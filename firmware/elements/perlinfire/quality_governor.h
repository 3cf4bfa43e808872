// Automatic quality for the Perlin fire: fed the measured time of each frame,
// it steps down a ladder of quality levels (ray steps, octaves, render scale)
// while frames are over budget and steps back up when they are comfortably
// under it. Hysteresis keeps it from oscillating: a level is left downwards
// only when over budget and upwards only when well under; it also remembers
// how much dearer each level was than the one below when it last saw both,
// and does not climb to a level predicted to break the budget again. A raise
// that still has to be taken back doubles the wait before the next one.
// GL-free and allocation-free once built, so it is unit-tested directly.
#pragma once

#include <cstddef>
#include <vector>

namespace candela {

struct QualityLevel {
  int steps = 24;      // ray-march steps through the volume
  int octaves = 3;     // noise octaves summed per step
  float scale = 1.0f;  // render scale (fraction of the screen's width and height)
  bool operator==(const QualityLevel&) const = default;
};

class QualityGovernor {
 public:
  struct Settings {
    double budget_ms = 1000.0 / 30;  // the frame time to hold
    int window = 16;                 // frames averaged per decision
    int warmup = 8;                  // frames ignored at start and after a change
    double lower_above = 1.05;       // step down when the mean is over budget * this
    double raise_below = 0.7;        // step up when the mean is under budget * this ...
    int raise_after = 3;             // ... for this many windows in a row (doubled on each retreat)
    int max_raise_after = 64;
    double predicted_below = 0.9;  // ... and the level above is predicted under budget * this
    // Far over budget (a big screen, a slow board), waiting whole windows
    // would show seconds of slow frames on the way down: a few frames over
    // budget * far_above are enough to step down (two levels when over
    // twice that), after a shorter warm-up.
    double far_above = 2.0;
    int quick_window = 3;
    int quick_warmup = 1;
  };

  // The ladder from `top` (best) down to the floors: each rung lowers one of
  // render scale, steps or octaves in turn.
  static std::vector<QualityLevel> make_ladder(QualityLevel top, int min_steps = 6,
                                               int min_octaves = 1, float min_scale = 0.25f);

  QualityGovernor(std::vector<QualityLevel> ladder, Settings settings);

  // One frame's time in ms; returns true when the level changed.
  bool add_frame(double frame_ms);

  int level() const { return level_; }  // 0 = best
  int levels() const { return static_cast<int>(ladder_.size()); }
  const QualityLevel& current() const { return ladder_[static_cast<std::size_t>(level_)]; }
  const QualityLevel& at(int level) const { return ladder_[static_cast<std::size_t>(level)]; }
  int changes() const { return changes_; }

 private:
  void change_to(int level, int warmup);
  std::vector<QualityLevel> ladder_;
  // ratio_[l]: mean frame time at level l - 1 over that at level l, when last
  // seen one after the other (0: not yet).
  std::vector<double> ratio_;
  double left_mean_ = 0;  // the mean at the level just left, until the new level's first window
  Settings s_;
  int level_ = 0;
  int skip_ = 0;
  int count_ = 0;
  double sum_ = 0;
  int good_windows_ = 0;
  int raise_after_ = 0;
  int left_level_ = -1;
  int raised_from_ = -1;  // the level left upwards in the last raise, while on probation
  int changes_ = 0;
};

}  // namespace candela
