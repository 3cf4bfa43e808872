#include "app/frame_pacing.h"

#include <algorithm>
#include <thread>

namespace candela {

FramePacer::FramePacer(bool paced_by_vsync, bool realtime, int steps_per_second, int fps,
                       uint64_t max_frames)
    : lockstep_(!paced_by_vsync && !realtime),
      self_paced_(!paced_by_vsync && realtime),
      fps_(fps > 0 ? fps : 60),
      steps_per_frame_(std::max(1, steps_per_second / fps_)),
      frame_period_(std::chrono::nanoseconds(1'000'000'000LL / fps_)),
      max_frames_(max_frames),
      prev_begin_(Clock::now()) {}

FramePacer::Due FramePacer::begin_frame(Clock::time_point begin, StepClock& clock) {
  Due due;
  const auto since = begin - prev_begin_;
  if (frames_ > 0)
    due.steps = lockstep_
                    ? steps_per_frame_
                    : clock.advance_wall(
                          std::chrono::duration_cast<std::chrono::nanoseconds>(since).count());
  prev_begin_ = begin;
  // The glide's step: a frame period in lockstep; else the wall time, at most a quarter second.
  const double since_ms = std::chrono::duration<double, std::milli>(since).count();
  due.seconds = lockstep_ ? 1.0f / static_cast<float>(fps_)
                          : static_cast<float>(std::min(since_ms, 250.0) / 1000.0);
  return due;
}

void FramePacer::end_frame(Clock::time_point begin) {
  ++frames_;
  if (self_paced_) std::this_thread::sleep_until(begin + frame_period_);
}

void FramePacer::count_asleep(Clock::time_point now) {
  if (!asleep_since_) {
    asleep_since_ = now;
    return;
  }
  const int64_t periods = (now - *asleep_since_) / frame_period_;
  frames_asleep_ += static_cast<uint64_t>(periods);
  *asleep_since_ += periods * frame_period_;
}

int FramePacer::sleep_ms() const {
  if (max_frames_ == 0) return 250;
  const uint64_t left = max_frames_ - std::min(max_frames_, frames_ + frames_asleep_);
  const int64_t periods = static_cast<int64_t>(std::min<uint64_t>(left, 1'000'000));
  const auto left_ms = std::chrono::ceil<std::chrono::milliseconds>(periods * frame_period_);
  return static_cast<int>(std::clamp<int64_t>(left_ms.count(), 1, 250));
}

}  // namespace candela
