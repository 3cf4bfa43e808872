// When the frame loop draws and how far the animation moves between frames
// (app/frame_loop.cpp): in lockstep with frames where nothing paces
// presentation (headless, --bench: deterministic output), by wall time where
// vsync or --realtime does. Also the frame periods that pass with nothing
// shown (screen off, no monitor), which count toward --frames so a bounded
// run ends whatever its schedule does. No GL, no allocation.
#pragma once

#include <chrono>
#include <cstdint>
#include <optional>

#include "core/clock.h"

namespace candela {

class FramePacer {
 public:
  using Clock = std::chrono::steady_clock;

  // paced_by_vsync: Display::paced_by_vsync(). realtime: hold `fps` by the
  // wall clock where nothing else does. max_frames 0: no end.
  FramePacer(bool paced_by_vsync, bool realtime, int steps_per_second, int fps,
             uint64_t max_frames);

  bool lockstep() const { return lockstep_; }
  // Frames drawn and periods asleep: another frame is wanted.
  bool more() const { return max_frames_ == 0 || frames_ + frames_asleep_ < max_frames_; }
  uint64_t frames() const { return frames_; }
  uint64_t frames_asleep() const { return frames_asleep_; }

  // A frame begins at `begin`: the steps due before it is drawn (none before
  // the first frame: it shows the state after the first step) and the
  // seconds it stands for (the brightness glide's and cross-fade's step).
  struct Due {
    int steps = 0;
    float seconds = 0.0f;
  };
  Due begin_frame(Clock::time_point begin, StepClock& clock);
  // The frame was presented. Self-paced: sleeps out the rest of its period.
  void end_frame(Clock::time_point begin);
  // The animation resumes at `now` without catching up on the time before
  // (the screen back on, a screen plugged in again).
  void resume(Clock::time_point now) { prev_begin_ = now; }

  // Nothing shown: counts the frame periods passed since the sleep began
  // (call before and after each wait), and the longest a wait may last (a
  // quarter second, less when --frames ends sooner).
  void count_asleep(Clock::time_point now);
  void awake() { asleep_since_.reset(); }
  int sleep_ms() const;

 private:
  bool lockstep_, self_paced_;
  int fps_, steps_per_frame_;
  Clock::duration frame_period_;
  uint64_t max_frames_;
  uint64_t frames_ = 0, frames_asleep_ = 0;
  Clock::time_point prev_begin_;
  std::optional<Clock::time_point> asleep_since_;
};

}  // namespace candela
