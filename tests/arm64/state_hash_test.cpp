// Scene::hash_state (what arm64_state_equality compares between builds)
// sees each element's own state, not only the clock: the same seed gives the
// same hash, another seed (other noise phases, another walk) another, and
// one fixed step more changes it.
#include "core/state_hash.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <string>

#include "core/clock.h"
#include "scene/scene.h"
#include "scene/scene_file.h"
#include "support/render_harness.h"

namespace {

uint64_t hash_after(const std::string& scene, uint64_t seed, uint64_t steps) {
  candela::SceneDesc desc = candela::load_builtin_scene(scene);
  const int sps = desc.steps_per_second;
  candela::test::RenderHarness harness(std::move(desc), 32, 18, seed);
  candela::StepClock clock(sps);
  candela::StepContext step;
  step.dt = clock.step_seconds();
  for (uint64_t i = 0; i < steps; ++i) {
    step.step = clock.steps();
    step.time = clock.seconds();
    harness.scene().update(step);
    clock.tick();
  }
  candela::StateHash h;
  harness.scene().hash_state(h);
  return h.value();
}

class StateHashOf : public testing::TestWithParam<const char*> {};

TEST_P(StateHashOf, FollowsTheSeedAndTheStep) {
  const uint64_t a = hash_after(GetParam(), 3, 120);
  EXPECT_EQ(a, hash_after(GetParam(), 3, 120)) << "the same seed and steps";
  EXPECT_NE(a, hash_after(GetParam(), 4, 120)) << "another seed: other element state";
  EXPECT_NE(a, hash_after(GetParam(), 3, 121)) << "one step more";
}

// Candles (noise phases, pendulums), an eigen-flame's graph walk and a story.
INSTANTIATE_TEST_SUITE_P(Scenes, StateHashOf,
                         testing::Values("default", "eigen-candle", "eigen-fireplace"));

TEST(StateHash, DependsOnTheOrderOfValues) {
  candela::StateHash ab, ba;
  ab.add(int32_t{1});
  ab.add(int32_t{2});
  ba.add(int32_t{2});
  ba.add(int32_t{1});
  EXPECT_NE(ab.value(), ba.value());
  candela::StateHash f1, f2;
  f1.add(candela::Fixed::from_raw(1));
  f2.add(candela::Fixed::from_raw(2));
  EXPECT_NE(f1.value(), f2.value()) << "one raw unit of a Fixed";
}

}  // namespace
