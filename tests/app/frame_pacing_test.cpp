// The frame loop's pacing (app/frame_pacing.h) and the kiosk's brightness
// glide (app/kiosk_post.h), without a display: how far the animation moves
// per frame, what counts toward --frames, how long a sleep may last.
#include "app/frame_pacing.h"

#include <gtest/gtest.h>

#include <chrono>

#include "app/kiosk_post.h"
#include "core/clock.h"

namespace candela {
namespace {

using std::chrono::milliseconds;

TEST(FramePacer, LockstepMovesAFramesWorthOfStepsWhateverTheWallClockSays) {
  FramePacer pace(/*paced_by_vsync=*/false, /*realtime=*/false, 60, 30, 0);
  EXPECT_TRUE(pace.lockstep());
  StepClock clock(60);
  const auto t0 = FramePacer::Clock::now();
  pace.resume(t0);
  FramePacer::Due due = pace.begin_frame(t0 + milliseconds(500), clock);
  EXPECT_EQ(due.steps, 0);  // frame 0 shows the first step's state
  EXPECT_FLOAT_EQ(due.seconds, 1.0f / 30);
  pace.end_frame(t0);
  due = pace.begin_frame(t0 + milliseconds(501), clock);  // 1 ms later or 500: the same
  EXPECT_EQ(due.steps, 2);                                // 60 steps a second at 30 fps
  EXPECT_FLOAT_EQ(due.seconds, 1.0f / 30);
}

TEST(FramePacer, ByVsyncTheStepsFollowTheWallClockAndCatchUpAtMostEight) {
  FramePacer pace(/*paced_by_vsync=*/true, false, 60, 60, 0);
  EXPECT_FALSE(pace.lockstep());
  StepClock clock(60);
  const auto t0 = FramePacer::Clock::now();
  pace.resume(t0);
  pace.begin_frame(t0, clock);
  pace.end_frame(t0);
  FramePacer::Due due = pace.begin_frame(t0 + milliseconds(50), clock);
  EXPECT_EQ(due.steps, 3);  // 50 ms of 16.7 ms steps
  EXPECT_NEAR(due.seconds, 0.05f, 1e-6);
  pace.end_frame(t0);
  due = pace.begin_frame(t0 + milliseconds(50) + std::chrono::seconds(3), clock);  // a stall
  EXPECT_EQ(due.steps, 8);                     // not minutes replayed at once
  EXPECT_FLOAT_EQ(due.seconds, 0.25f);         // the glide's step is capped too
  pace.resume(t0 + std::chrono::seconds(10));  // the screen back on: no catching up
  pace.end_frame(t0);
  due = pace.begin_frame(t0 + std::chrono::seconds(10) + milliseconds(17), clock);
  EXPECT_EQ(due.steps, 1);
}

TEST(FramePacer, PeriodsAsleepCountTowardFramesAndShortenTheLastSleep) {
  FramePacer pace(false, false, 60, 10, /*max_frames=*/12);  // 100 ms periods
  const auto t0 = FramePacer::Clock::now();
  EXPECT_EQ(pace.sleep_ms(), 250);  // 12 periods left: a quarter second at most
  pace.count_asleep(t0);            // the sleep begins
  pace.count_asleep(t0 + milliseconds(1050));
  EXPECT_EQ(pace.frames_asleep(), 10u);
  EXPECT_EQ(pace.sleep_ms(), 200);  // 2 periods left
  EXPECT_TRUE(pace.more());
  pace.count_asleep(t0 + milliseconds(1250));  // counted from 1000 ms, not 1050
  EXPECT_EQ(pace.frames_asleep(), 12u);
  EXPECT_FALSE(pace.more());  // a bounded run ends although nothing was shown
  pace.awake();
  pace.count_asleep(t0 + milliseconds(5000));  // a new sleep starts its own count
  EXPECT_EQ(pace.frames_asleep(), 12u);
}

TEST(BrightnessGlide, CrossesTheWholeRangeInAQuarterSecondAndFadesTheOldFrame) {
  BrightnessGlide glide;
  glide.fade_left_s = 1.0f;
  for (int i = 0; i < 14; ++i) glide.step(1.0f / 60, 0.0f);
  EXPECT_NEAR(glide.level, 1.0f / 15, 1e-5);  // no faster than the quarter second (no flash)
  glide.step(1.0f / 60, 0.0f);
  EXPECT_NEAR(glide.level, 0.0f, 1e-5);  // 15 frames at 60 fps: there (no lag)
  EXPECT_NEAR(glide.old_alpha(1.0f), 0.75f, 1e-5);
  glide.level = 0.0f;
  glide.step(1.0f / 60, 0.5f);
  EXPECT_NEAR(glide.level, 4.0f / 60, 1e-6);  // one frame's worth toward the target
  glide.step(2.0f, 0.5f);
  EXPECT_FLOAT_EQ(glide.level, 0.5f);  // reaches it, does not overshoot
  EXPECT_FLOAT_EQ(glide.old_alpha(1.0f), 0.0f);
  EXPECT_FLOAT_EQ(glide.old_alpha(0.0f), 0.0f);  // no cross-fade
}

}  // namespace
}  // namespace candela
