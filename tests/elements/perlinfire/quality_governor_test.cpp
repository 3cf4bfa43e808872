// The automatic quality mode, fed frame times from a cost model of the fire
// (time grows with pixels x steps x octaves): it must step down to what the
// budget allows, settle there, and come back up when frames get cheap.
#include "elements/perlinfire/quality_governor.h"

#include <gtest/gtest.h>

#include "core/random.h"

namespace candela {
namespace {

const QualityLevel kTop{24, 4, 1.0f};

double cost_ms(const QualityLevel& q, double full_ms) {
  return 2.0 + full_ms * q.scale * q.scale * q.steps * q.octaves / (24.0 * 4.0);
}

TEST(QualityGovernor, LadderOnlyEverLowersQuality) {
  const auto ladder = QualityGovernor::make_ladder(kTop, 6, 1, 0.25f);
  ASSERT_GE(ladder.size(), 6u);
  EXPECT_EQ(ladder.front(), kTop);
  for (size_t i = 1; i < ladder.size(); ++i) {
    EXPECT_LT(cost_ms(ladder[i], 100), cost_ms(ladder[i - 1], 100));
    EXPECT_GE(ladder[i].steps, 6);
    EXPECT_GE(ladder[i].octaves, 1);
    EXPECT_GE(ladder[i].scale, 0.25f);
  }
  EXPECT_EQ(ladder.back(), (QualityLevel{6, 1, 0.25f}));
}

TEST(QualityGovernor, SlowFramesStepQualityDownAndItSettles) {
  QualityGovernor::Settings s;
  s.budget_ms = 1000.0 / 30;
  QualityGovernor g(QualityGovernor::make_ladder(kTop), s);
  Pcg32 rng(3);
  const double full_ms = 400;  // far over budget at the top level
  int last_change_frame = 0, downs = 0, ups = 0;
  int prev_level = 0;
  for (int frame = 0; frame < 6000; ++frame) {
    const double jitter = 0.9 + 0.2 * rng.unit_double();  // +-10 % measurement noise
    if (g.add_frame(cost_ms(g.current(), full_ms) * jitter)) {
      last_change_frame = frame;
      (g.level() > prev_level ? downs : ups)++;
      prev_level = g.level();
    }
  }
  EXPECT_GT(downs, 3);
  EXPECT_LE(ups, 3);                   // a few probes upwards at most
  EXPECT_LT(last_change_frame, 3000);  // then nothing for thousands of frames
  // It holds the budget, and the level above would not have.
  EXPECT_LE(cost_ms(g.current(), full_ms), s.budget_ms * s.lower_above);
  ASSERT_GT(g.level(), 0);
  EXPECT_GT(cost_ms(g.at(g.level() - 1), full_ms), s.budget_ms * s.raise_below);
}

TEST(QualityGovernor, FarOverBudgetItComesDownInAFewFramesPerLevel) {
  // A fire 12x over budget at its top level (a big screen on a slow board):
  // waiting whole windows (24 frames a level) would show seconds of slow frames.
  QualityGovernor::Settings s;
  s.budget_ms = 1000.0 / 30;
  QualityGovernor g(QualityGovernor::make_ladder(kTop), s);
  int frame = 0;
  while (frame < 1000 && cost_ms(g.current(), 400) > 2 * s.budget_ms)
    g.add_frame(cost_ms(g.current(), 400)), ++frame;
  // Five levels down (402 ms -> 52 ms) in under 25 frames (whole windows: 128).
  EXPECT_LT(frame, 25);
  // Within twice the budget, the ordinary windows take over and bring it inside.
  for (int i = 0; i < 600; ++i) g.add_frame(cost_ms(g.current(), 400));
  EXPECT_LE(cost_ms(g.current(), 400), s.budget_ms * s.lower_above);
  EXPECT_GT(cost_ms(g.at(g.level() - 1), 400), s.budget_ms * s.raise_below);
}

TEST(QualityGovernor, CheapFramesBringQualityBack) {
  QualityGovernor g(QualityGovernor::make_ladder(kTop), {});
  for (int i = 0; i < 2000; ++i) g.add_frame(cost_ms(g.current(), 400));
  ASSERT_GT(g.level(), 2);
  for (int i = 0; i < 4000; ++i) g.add_frame(cost_ms(g.current(), 10));
  EXPECT_EQ(g.level(), 0);
}

TEST(QualityGovernor, ARaiseThatFailsIsTriedLessAndLessOften) {
  // Level 1 fits well under budget, level 0 is far over it: without
  // hysteresis this would flip every few windows.
  std::vector<QualityLevel> ladder{{24, 4, 1.0f}, {12, 4, 1.0f}};
  QualityGovernor::Settings s;
  s.budget_ms = 20;
  QualityGovernor g(ladder, s);
  int changes_first = 0, changes_last = 0;
  for (int frame = 0; frame < 20000; ++frame) {
    const bool changed = g.add_frame(g.level() == 0 ? 30.0 : 10.0);
    if (changed && frame < 2000) ++changes_first;
    if (changed && frame >= 10000) ++changes_last;
  }
  EXPECT_GT(changes_first, changes_last);
  EXPECT_LE(changes_last, 4);
}

TEST(QualityGovernor, IgnoresWarmUpFrames) {
  QualityGovernor::Settings s;
  s.warmup = 8;
  s.window = 4;
  QualityGovernor g(QualityGovernor::make_ladder(kTop), s);
  for (int i = 0; i < 8; ++i) EXPECT_FALSE(g.add_frame(1000.0));  // shader compiles, first frames
  for (int i = 0; i < 4; ++i) g.add_frame(1.0);
  EXPECT_EQ(g.level(), 0);
}

}  // namespace
}  // namespace candela
