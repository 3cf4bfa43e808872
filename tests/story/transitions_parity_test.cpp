// The story planner's transitions (firmware/story/weight_transitions.h, no
// Eigen, run on the device) find the same paths as candela-tool's
// (tools/model/transitions.h) on the built-in candle model.
#include <gtest/gtest.h>

#include "model/flame_model.h"
#include "model_views.h"
#include "story/weight_transitions.h"
#include "transitions.h"

namespace candela {
namespace {

TEST(StoryTransitions, SamePathsAsTheToolsEigenTransitions) {
  const auto m =
      model::FlameModel::load(std::string(CANDELA_SOURCE_DIR) + "/firmware/models/default.cmodel");
  const int dims = 50;
  const tools::WeightSpace ref = tools::model_space(m, dims);
  const story::WeightTable mine = story::WeightTable::of(m, dims);
  const float theta = 0.5f * mine.median_step();
  int grown = 0;
  for (const auto& [alpha, beta] : std::vector<std::pair<int, int>>{
           {299, 1200}, {1499, 3000}, {3299, 52}, {900, 2500}, {100, 700}, {2000, 3500}}) {
    SCOPED_TRACE(std::to_string(alpha) + " -> " + std::to_string(beta));
    EXPECT_NEAR(mine.distance(alpha, beta), ref.distance(alpha, beta),
                1e-4f * ref.distance(alpha, beta));
    for (int steps : {4, 20}) {
      tools::TransitionOptions o;
      o.steps = steps;
      o.theta_min = theta;
      o.reject_tail = 3;
      const story::PathOptions p{steps, theta, 3};
      const tools::Transition rb = tools::direct_bridging(ref, alpha, beta, o);
      const story::FramePath mb = story::direct_bridging(mine, alpha, beta, p);
      EXPECT_EQ(mb.path, rb.path) << "bridge, N = " << steps;
      const tools::Transition rg = tools::end_growing(ref, alpha, beta, o);
      const story::FramePath mg = story::end_growing(mine, alpha, beta, p);
      EXPECT_EQ(mg.found, rg.found) << rg.how;
      EXPECT_EQ(mg.how, rg.how);
      EXPECT_EQ(mg.path, rg.path) << "grow, steps = " << steps;
      grown += mg.found;
    }
  }
  EXPECT_GT(grown, 0) << "some grown path connected";
  // Low-pass: the same four rewritten rows.
  const std::vector<int> t1{297, 298, 299}, t2{1200, 1201, 1202};
  const Eigen::MatrixXf rl =
      tools::lowpass_transition(tools::model_weights(m), t1, t2, {1 / 3.f, 1 / 3.f, 1 / 3.f}, 50);
  const std::vector<float> ml = story::lowpass_rows(mine, t1, t2, {1 / 3.f, 1 / 3.f, 1 / 3.f}, 50);
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < m.components(); ++c)
      EXPECT_NEAR(ml[static_cast<size_t>(r) * m.components() + c], rl(r, c),
                  1e-3f * (1 + std::fabs(rl(r, c))));
}

}  // namespace
}  // namespace candela
