// Transitions on a point set whose answers are known, on a real clip, and the
// motion graph.
#include "transitions.h"

#include <gtest/gtest.h>

#include <cstdio>

#include "model_build.h"
#include "model_test_support.h"

namespace ct = candela::tools;

namespace {

// Frames as 2-D points: alpha = 0 at (0,0), beta = 1 at (10,0); frames 6, 2, 7
// lie near the line between them, the others stray.
ct::WeightSpace points() {
  Eigen::MatrixXf w(8, 2);
  w << 0, 0,        // 0 alpha
      10, 0,        // 1 beta
      5, 0.2f,      // 2 midpoint
      5, 3,         // 3 above the midpoint
      2.5f, -4,     // 4
      7.5f, 4,      // 5
      2.4f, 0.1f,   // 6 a quarter of the way
      7.6f, -0.1f;  // 7 three quarters
  return ct::WeightSpace::from(w, {});
}

}  // namespace

TEST(Transitions, DirectBridgingTakesTheFramesNearestTheLine) {
  ct::TransitionOptions o;
  o.reject_tail = 0;
  o.theta_min = 1;
  o.steps = 1;
  EXPECT_EQ(ct::direct_bridging(points(), 0, 1, o).path, (std::vector<int>{0, 2, 1}));
  o.steps = 3;
  EXPECT_EQ(ct::direct_bridging(points(), 0, 1, o).path, (std::vector<int>{0, 6, 2, 7, 1}));
}

TEST(Transitions, EndGrowingMeetsAtTheSharedFrame) {
  ct::TransitionOptions o;
  o.reject_tail = 0;
  o.theta_min = 1;
  o.steps = 10;
  ct::Transition t = ct::end_growing(points(), 0, 1, o);
  EXPECT_TRUE(t.found);
  EXPECT_EQ(t.how, "shared image");
  EXPECT_EQ(t.path, (std::vector<int>{0, 6, 2, 7, 1}));
}

TEST(Transitions, EndGrowingRespectsThetaMinAndRejections) {
  ct::TransitionOptions o;
  o.reject_tail = 0;
  o.steps = 10;
  // With theta_min 3 the quarter points (2.4 away) are too close to the ends;
  // the midpoint is then reached directly from both ends.
  o.theta_min = 3;
  ct::Transition t = ct::end_growing(points(), 0, 1, o);
  ASSERT_TRUE(t.found) << t.how;
  EXPECT_EQ(t.path, (std::vector<int>{0, 2, 1}));
  // A frame just before alpha in its clip is never used: clip = frames 0..7 in
  // the order 6, 0, ... would make 6 the frame before alpha.
  Eigen::MatrixXf w = points().w;
  Eigen::MatrixXf re(8, 2);
  re.row(0) = w.row(6);  // frame 0 is now the quarter point, right before alpha
  re.row(1) = w.row(0);  // alpha
  for (int i = 2; i < 8; ++i) re.row(i) = w.row(i == 6 ? 1 : i);  // frame 6 is beta
  candela::model::ClipInfo clip;
  clip.first = 0;
  clip.count = 8;
  ct::WeightSpace s = ct::WeightSpace::from(re, {clip});
  o.theta_min = 1;
  o.reject_tail = 1;
  t = ct::end_growing(s, 1, 6, o);
  ASSERT_TRUE(t.found) << t.how;
  for (int f : t.path) EXPECT_NE(f, 0) << "the frame before alpha was used";
}

TEST(Transitions, LowPassAveragesAcrossTheJoin) {
  Eigen::MatrixXf w(6, 2);
  w << 0, 9, 0, 9, 0, 9, 3, 9, 3, 9, 3, 9;  // T1 = 0..2 at 0, T2 = 3..5 at 3 (first component)
  Eigen::MatrixXf out =
      ct::lowpass_transition(w, {0, 1, 2}, {3, 4, 5}, {1 / 3.f, 1 / 3.f, 1 / 3.f}, 1);
  EXPECT_NEAR(out(0, 0), 0.0f, 1e-6);
  EXPECT_NEAR(out(1, 0), 1.0f, 1e-6);  // (0 + 0 + 3) / 3
  EXPECT_NEAR(out(2, 0), 2.0f, 1e-6);
  EXPECT_NEAR(out(3, 0), 3.0f, 1e-6);
  for (int r = 0; r < 4; ++r)
    EXPECT_EQ(out(r, 1), 9.0f) << "components past the filtered ones are kept";
}

class RealClipTransitions : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dataset_ = new ct::Dataset(ct::test::small_dataset("candle_breeze_tfg_flameshaken", 48, 80, 1));
    ct::BuildOptions o;
    o.pca.components = 24;
    o.holdout_every = 0;
    o.learning_flames = false;
    model_ = new ct::BuiltModel(ct::build_model(*dataset_, o));
  }
  static void TearDownTestSuite() {
    delete model_;
    delete dataset_;
  }
  static ct::Dataset* dataset_;
  static ct::BuiltModel* model_;
};
ct::Dataset* RealClipTransitions::dataset_ = nullptr;
ct::BuiltModel* RealClipTransitions::model_ = nullptr;

TEST_F(RealClipTransitions, EveryStepIsBetweenThetaMinAndTheEndsDistance) {
  ct::WeightSpace s = ct::WeightSpace::from(model_->pca.weights, dataset_->clips);
  ct::TransitionOptions o;
  // Steps of about one natural frame-to-frame change.
  // Steps of at least the motion graph's own smallest step (half the median
  // frame-to-frame change), as `build` uses it.
  o.theta_min = model_->graph.theta_min;
  o.steps = 40;
  int found = 0;
  // Upright flame -> strongly bent, and back, and two calm stretches.
  for (auto [a, b] :
       {std::pair{20, 80}, std::pair{90, 200}, std::pair{10, 240}, std::pair{150, 30}}) {
    ct::Transition t = ct::end_growing(s, a, b, o);
    const float D = s.distance(a, b);
    std::printf("%d -> %d (distance %.1f, theta_min %.1f): %s, %zu frames\n", a, b, D, o.theta_min,
                t.how.c_str(), t.path.size());
    if (!t.found) continue;
    ++found;
    ASSERT_GE(t.path.size(), 2u);
    EXPECT_EQ(t.path.front(), a);
    EXPECT_EQ(t.path.back(), b);
    for (size_t i = 0; i + 1 < t.path.size(); ++i) {
      const float step = s.distance(t.path[i], t.path[i + 1]);
      EXPECT_LT(step, D) << a << "->" << b << " step " << i;
      EXPECT_GE(step, o.theta_min) << a << "->" << b << " step " << i;
    }
  }
  // Half of these far pairs (upright to strongly bent) connect on display-
  // encoded gray; on linear gray three of four did. Every path found is checked above.
  EXPECT_GE(found, 2) << "End Growing should connect half the far pairs on one clip";
}

TEST_F(RealClipTransitions, MotionGraphAlwaysHasSomewhereToGo) {
  const ct::MotionGraphData& g = model_->graph;
  const int n = dataset_->frames();
  ASSERT_EQ(static_cast<int>(g.offsets.size()), n + 1);
  ct::WeightSpace s = ct::WeightSpace::from(model_->pca.weights, dataset_->clips);
  int jumps = 0;
  for (int i = 0; i < n; ++i) {
    ASSERT_GT(g.offsets[i + 1], g.offsets[i]) << "frame " << i << " is a dead end";
    for (int e = g.offsets[i]; e < g.offsets[i + 1]; ++e) {
      const int j = g.successors[e];
      ASSERT_GE(j, 0);
      ASSERT_LT(j, n);
      EXPECT_FLOAT_EQ(g.cost[e], s.distance(i, j));
      if (j == i + 1) continue;
      ++jumps;
      EXPECT_GE(std::abs(j - i), 12) << "a jump replays the neighbourhood";
      if (i + 1 < n) {
        EXPECT_GE(g.cost[e], g.theta_min * 0.999f);
      }
    }
  }
  EXPECT_GT(jumps, n / 2) << "the graph should offer many ways out";
}
