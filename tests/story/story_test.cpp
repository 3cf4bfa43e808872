// Stories: the file's validation, the planner's joints (each transition
// within the seam bound where a hard cut is not), the player that the
// runtime's story driver runs, and determinism.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "story/story_file.h"
#include "story/story_plan.h"
#include "story/story_player.h"
#include "story_test_model.h"

namespace candela::story {
namespace {

std::string error_of(const std::string& text) {
  try {
    load_story_text(text, "tour.toml");
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST(StoryFile, ReadsSegmentsTransitionsAndRepeats) {
  const StoryDesc s = load_story_text(R"(
model = "builtin:fire"
seed = 5
loop = false
[[segment]]
clip = "T1"
to = 98
[[segment]]
walk = 2.5
repeat = 3
transition = { method = "bridge", steps = 7, theta_min = 0.25, reject_tail = 0 }
[[segment]]
arp = 1.0
transition = { method = "lowpass", kernel = [0.2, 0.2, 0.6], components = 20 }
[[segment]]
from = 10
to = 40
transition = { method = "cut" }
)",
                                      "tour.toml");
  EXPECT_EQ(s.model, "builtin:fire");
  EXPECT_TRUE(s.has_seed);
  EXPECT_EQ(s.seed, 5u);
  EXPECT_FALSE(s.loop);
  ASSERT_EQ(s.segments.size(), 4u);
  EXPECT_EQ(s.segments[0].kind, SegmentKind::kFrames);
  EXPECT_EQ(s.segments[0].clip, "T1");
  EXPECT_EQ(s.segments[0].to, 98);
  EXPECT_EQ(s.segments[0].transition.method, Method::kGrow);  // the default
  EXPECT_EQ(s.segments[0].transition.steps, 20);
  EXPECT_EQ(s.segments[1].kind, SegmentKind::kWalk);
  EXPECT_DOUBLE_EQ(s.segments[1].seconds, 2.5);
  EXPECT_EQ(s.segments[1].repeat, 3);
  EXPECT_EQ(s.segments[1].transition.method, Method::kBridge);
  EXPECT_EQ(s.segments[1].transition.steps, 7);
  EXPECT_FLOAT_EQ(s.segments[1].transition.theta_min, 0.25f);
  EXPECT_EQ(s.segments[1].transition.reject_tail, 0);
  EXPECT_EQ(s.segments[2].kind, SegmentKind::kArp);
  EXPECT_FLOAT_EQ(s.segments[2].transition.kernel[2], 0.6f);
  EXPECT_EQ(s.segments[2].transition.components, 20);
  EXPECT_EQ(s.segments[3].clip, "");
  EXPECT_EQ(s.segments[3].from, 10);
  EXPECT_EQ(s.segments[3].transition.method, Method::kCut);
  // A model path is relative to the story file.
  EXPECT_EQ(story_model_path(load_story_text("model = \"m.cmodel\"\n[[segment]]\nwalk = 1\n",
                                             "/srv/stories/tour.toml")),
            "/srv/stories/m.cmodel");
}

TEST(StoryFile, ErrorsNameTheFileTheKeyAndWhatWasExpected) {
  const std::string head = "model = \"builtin:fire\"\n";
  struct Case {
    std::string text, want;
  };
  for (const Case& c : std::vector<Case>{
           {"[[segment]]\nwalk = 1\n", "tour.toml: model: expected the model"},
           {head, "tour.toml: segment: expected at least one [[segment]]"},
           {head + "[[segment]]\nrepeat = 2\n",
            "tour.toml: segment[0].clip: expected exactly one of"},
           {head + "[[segment]]\nwalk = 1\narp = 1\n",
            "tour.toml: segment[0].arp: expected exactly one"},
           {head + "[[segment]]\nwalk = 1000\n",
            "tour.toml: segment[0].walk: expected a number in"},
           {head + "[[segment]]\nclip = \"a\"\nrepeat = 0\n", "tour.toml: segment[0].repeat:"},
           {head + "[[segment]]\nclip = \"a\"\nfrom = 10\nto = 12\n",
            "tour.toml: segment[0].to: expected at least 4 frames"},
           {head + "[[segment]]\nwalk = 1\ntransition = { method = \"morph\" }\n",
            "tour.toml: segment[0].transition.method: expected one of"},
           {head + "[[segment]]\nwalk = 1\ntransition = { method = \"lowpass\", kernel = [0.5, "
                   "0.5, 0.5] }\n",
            "tour.toml: segment[0].transition.kernel: expected taps that sum to 1"},
           {head + "[[segment]]\nwalk = 1\ntransition = { method = \"lowpass\", steps = 3 }\n",
            "tour.toml: segment[0].transition.steps"},  // a bridge/grow key on a low-pass
           {head + "[[segment]]\nwalk = 1\ntransition = { method = \"bridge\", steps = 201 }\n",
            "tour.toml: segment[0].transition.steps: expected"},
           {head + "[[segment]]\nwalk = 1\nspeed = 2\n", "tour.toml: segment[0].speed"},
           {head + "colour = 1\n[[segment]]\nwalk = 1\n", "tour.toml: colour"},
           {head + "[[segment]\nwalk = 1\n", "tour.toml: line 2"},
       }) {
    const std::string e = error_of(c.text);
    EXPECT_EQ(e.rfind(c.want, 0), 0u) << "story:\n" << c.text << "\ngave: " << e;
  }
  // Bounded: more than kMaxSegments segments are refused.
  std::string many = head;
  for (size_t i = 0; i <= kMaxSegments; ++i) many += "[[segment]]\nwalk = 1\n";
  EXPECT_NE(error_of(many).find("tour.toml: segment: expected at most 64 segments"),
            std::string::npos);
  // A missing file names itself.
  try {
    load_story_file("/nonexistent/tour.toml");
    ADD_FAILURE() << "a missing story was read";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/tour.toml"), std::string::npos);
  }
}

TEST(StoryPlan, ErrorsNameTheSegmentKey) {
  const model::FlameModel m = test::two_clip_model();
  auto plan_error = [&](const std::string& seg) {
    try {
      plan_story(load_story_text("model = \"x\"\n[[segment]]\n" + seg, "tour.toml"), m, 1);
    } catch (const ConfigError& e) {
      return std::string(e.what());
    }
    return std::string("(planned)");
  };
  EXPECT_EQ(
      plan_error("clip = \"T3\"\n")
          .rfind("tour.toml: segment[0].clip: expected a clip of the model (\"T1\", \"middle\", "
                 "\"T2\"), got \"T3\"",
                 0),
      0u);
  EXPECT_EQ(plan_error("clip = \"T1\"\nto = 101\n")
                .rfind("tour.toml: segment[0].to: expected at most 100", 0),
            0u);
  EXPECT_EQ(plan_error("clip = \"T1\"\nfrom = 98\n")
                .rfind("tour.toml: segment[0].from: expected at least 4", 0),
            0u);
  EXPECT_EQ(
      plan_error("arp = 2\n")
          .rfind("tour.toml: segment[0].arp: expected a model with a Learning Flames part", 0),
      0u);
  EXPECT_EQ(plan_error("walk = 600\nrepeat = 100\n")
                .rfind("tour.toml: segment[0]: expected a story of at most 65536 frames", 0),
            0u);
}

// T1 + T2 + T2 + T1, looped, every joint made by `method`.
std::string t1_t2_t2_t1(const std::string& transition) {
  std::string s = "model = \"x\"\nloop = true\n";
  for (const char* clip : {"T1", "T2", "T2", "T1"})
    s += std::string("[[segment]]\nclip = \"") + clip + "\"\ntransition = " + transition + "\n";
  return s;
}

TEST(StoryPlan, EveryTransitionStaysWithinTheSeamBoundWhereAHardCutDoesNot) {
  const model::FlameModel m = test::two_clip_model();
  const StoryPlan cut = plan_story(load_story_text(t1_t2_t2_t1("{ method = \"cut\" }"), "t"), m, 1);
  EXPECT_NEAR(cut.median_step(), 1.0f, 0.01f);
  EXPECT_FLOAT_EQ(cut.seam_bound(), kMinSeamBound);
  ASSERT_EQ(cut.joints().size(), 4u);  // T1>T2, T2>T2, T2>T1, loop T1>T1
  EXPECT_EQ(cut.frames(), 4 * test::kLoopFrames);
  EXPECT_GT(cut.joints()[0].seam_ratio, 10 * cut.seam_bound()) << "T1 -> T2 is a far jump";
  EXPECT_GT(cut.joints()[2].seam_ratio, 10 * cut.seam_bound()) << "T2 -> T1 is a far jump";
  for (const char* method : {"bridge", "grow"}) {
    SCOPED_TRACE(method);
    const StoryPlan p = plan_story(
        load_story_text(t1_t2_t2_t1(std::string("{ method = \"") + method + "\" }"), "t"), m, 1);
    ASSERT_EQ(p.joints().size(), 4u);
    for (const JointReport& j : p.joints()) {
      std::printf("%-7s %-28s seam %.2f (cut %.2f), %d inserted: %s\n", method, j.what.c_str(),
                  j.seam_ratio, j.cut_ratio, j.inserted, j.how.c_str());
      EXPECT_LE(j.seam_ratio, p.seam_bound()) << j.what << ": " << j.how;
    }
    // The far joints went through the in-between frames; the story holds the
    // four clips and what the joints put in, nothing else.
    EXPECT_GE(p.joints()[0].inserted, test::kMiddleFrames / 3);
    int inserted = 0;
    for (const JointReport& j : p.joints()) inserted += j.inserted;
    EXPECT_EQ(p.frames(), 4 * test::kLoopFrames + inserted);
    for (int seg = 0; seg < 4; ++seg) EXPECT_EQ(p.pieces()[seg].count, test::kLoopFrames);
    EXPECT_GT(p.frames(), cut.frames());
    // And no step anywhere in the looped story is a seam, the wrap included.
    float worst = 0;
    for (int i = 0; i < p.frames(); ++i) worst = std::max(worst, p.step_ratio(i));
    EXPECT_LE(worst, p.seam_bound());
  }
  // Low-pass spreads a short jump over the joint (a cut of ~3 ordinary steps:
  // T1 without its last two frames, repeated) but not a far one.
  const std::string near = "model = \"x\"\n[[segment]]\nclip = \"T1\"\nto = 98\nrepeat = 2\n";
  const StoryPlan near_cut =
      plan_story(load_story_text(near + "transition = { method = \"cut\" }\n", "t"), m, 1);
  const StoryPlan near_lp =
      plan_story(load_story_text(near + "transition = { method = \"lowpass\" }\n", "t"), m, 1);
  ASSERT_EQ(near_lp.joints().size(), 2u);  // the repeat and the loop
  for (size_t i = 0; i < 2; ++i) {
    EXPECT_GT(near_cut.joints()[i].seam_ratio, near_cut.seam_bound());
    EXPECT_LE(near_lp.joints()[i].seam_ratio, near_lp.seam_bound());
    EXPECT_LT(near_lp.joints()[i].seam_ratio, 0.7f * near_cut.joints()[i].seam_ratio);
  }
  EXPECT_EQ(near_lp.frames(), near_cut.frames());  // low-pass rewrites, inserts nothing
  EXPECT_EQ(near_lp.model_frame(96), -1);          // T1's last two frames are blends now
  EXPECT_EQ(near_lp.model_frame(0), -1);           // and, for the loop, the story's first two
  EXPECT_EQ(near_lp.model_frame(2), 2);
  const StoryPlan far_lp =
      plan_story(load_story_text(t1_t2_t2_t1("{ method = \"lowpass\" }"), "t"), m, 1);
  EXPECT_GT(far_lp.joints()[0].seam_ratio, far_lp.seam_bound());
}

TEST(StoryPlan, SameSeedSameFramesAndSeedsDiffer) {
  const model::FlameModel m = test::two_clip_model();
  const StoryDesc s = load_story_text(
      "model = \"x\"\n[[segment]]\nclip = \"T1\"\n[[segment]]\nwalk = 6\n"
      "transition = { method = \"bridge\" }\n[[segment]]\nwalk = 6\n",
      "t");
  const StoryPlan a = plan_story(s, m, 7), b = plan_story(s, m, 7), c = plan_story(s, m, 8);
  ASSERT_EQ(a.frames(), b.frames());
  bool differs = a.frames() != c.frames();
  for (int i = 0; i < a.frames(); ++i) {
    ASSERT_TRUE(std::equal(a.weights_of(i), a.weights_of(i) + a.components(), b.weights_of(i)));
    if (!differs && i < c.frames()) differs = a.model_frame(i) != c.model_frame(i);
  }
  EXPECT_TRUE(differs) << "another seed walks elsewhere";
  // The walk follows the motion graph (but where its no-repeat guard refuses
  // every successor and it bridges to a near frame): most of its steps are edges.
  const PieceReport& walk = a.pieces()[1];
  EXPECT_EQ(walk.count, 180);  // 6 s at the model's 30 fps
  int edges = 0;
  for (int i = walk.first; i + 1 < walk.first + walk.count; ++i) {
    const int f = a.model_frame(i), g = a.model_frame(i + 1);
    const auto succ = m.graph.successors_of(f);
    edges += std::find(succ.begin(), succ.end(), g) != succ.end();
  }
  EXPECT_GT(edges, walk.count * 3 / 4);
}

// ARP synthesis on the built-in fire (it has a Learning Flames part): the
// seconds asked for at the model's rate, only frames the ARP was trained on
// (single-plume ones), the same frames for the same seed, others for another.
TEST(StoryPlan, ArpSegmentsShowTrainingFramesAndFollowTheSeed) {
  // The built-in candle (a fire is many plumes at once: its model has no
  // Learning Flames part).
  const model::FlameModel m =
      model::FlameModel::load(std::string(CANDELA_SOURCE_DIR) + "/firmware/models/default.cmodel");
  ASSERT_TRUE(m.has_learning_flames);
  const StoryDesc s = load_story_text("model = \"x\"\nloop = false\n[[segment]]\narp = 4.0\n", "t");
  const StoryPlan a = plan_story(s, m, 11), b = plan_story(s, m, 11), c = plan_story(s, m, 12);
  ASSERT_EQ(a.frames(), 240);  // 4 s at 60 fps
  ASSERT_EQ(b.frames(), 240);
  std::vector<int> multi;
  for (const auto& v : m.file().info()["multi_plume"]) multi.push_back(v.get<int>());
  int same = 0, distinct = 0;
  std::vector<int> seen;
  for (int i = 0; i < a.frames(); ++i) {
    ASSERT_EQ(a.model_frame(i), b.model_frame(i));
    EXPECT_EQ(std::find(multi.begin(), multi.end(), a.model_frame(i)), multi.end())
        << "frame " << a.model_frame(i) << " has several plumes: the ARP never saw it";
    same += a.model_frame(i) == c.model_frame(i);
    if (std::find(seen.begin(), seen.end(), a.model_frame(i)) == seen.end()) {
      seen.push_back(a.model_frame(i));
      ++distinct;
    }
  }
  EXPECT_LT(same, a.frames() / 2) << "another seed synthesises another flame";
  EXPECT_GT(distinct, a.frames() / 4) << "the synthesis moves, it does not hold a few frames";
  std::printf("arp: %d distinct frames of 120, largest step inside %.2f median steps\n", distinct,
              a.pieces()[0].max_step_ratio);
}

// Issue 34: the story limits did not bound the planning work. Each bridge or
// grow joint searches the model's frames, and repeats multiplied the joints:
// a valid story on the built-in candle planned for 72 s, on the thread that
// reads the control socket. A repeat's joint is now worked out once and
// replayed, so 100 repeats cost about what 2 do, and give the same joint.
TEST(StoryPlan, RepeatsReplayTheirJointRatherThanPlanItAgain) {
  const model::FlameModel m = test::two_clip_model();
  auto story = [](int repeat) {
    return "model = \"x\"\n[[segment]]\nclip = \"T1\"\n[[segment]]\nclip = \"T2\"\nto = 60\n"
           "repeat = " +
           std::to_string(repeat) + "\ntransition = { method = \"grow\" }\n";
  };
  const StoryPlan two = plan_story(load_story_text(story(2), "t"), m, 1);
  const StoryPlan hundred = plan_story(load_story_text(story(100), "t"), m, 1);
  ASSERT_EQ(two.joints().size(), 3u);        // T1 > T2, T2 repeat, loop T2 > T1
  ASSERT_EQ(hundred.joints().size(), 101u);  // T1 > T2, 99 repeats, the loop
  const JointReport& repeat = two.joints()[1];
  EXPECT_GT(repeat.inserted, 0) << "T2's end and start are far apart: the joint goes round";
  for (size_t k = 1; k < 100; ++k) {
    const JointReport& j = hundred.joints()[k];
    ASSERT_EQ(j.what, "segment[1] repeat " + std::to_string(k + 1));
    EXPECT_EQ(j.inserted, repeat.inserted) << j.what;
    EXPECT_EQ(j.how, repeat.how) << j.what;
    EXPECT_FLOAT_EQ(j.seam_ratio, repeat.seam_ratio) << j.what;
    for (int i = 0; i <= j.inserted; ++i)
      ASSERT_EQ(hundred.model_frame(j.first + i), two.model_frame(repeat.first + i)) << j.what;
  }
  std::printf("planning work: 2 repeats %llu, 100 repeats %llu component operations\n",
              static_cast<unsigned long long>(two.work()),
              static_cast<unsigned long long>(hundred.work()));
  EXPECT_LT(hundred.work(), 2 * two.work());
}

// Planning past kMaxPlanWork is refused as a ConfigError naming where it
// stopped, so `candela --check` fails on the story and no kiosk stalls on it:
// 600 s of ARP synthesis on the built-in candle (each of its 36,000 states
// compared with every training state) is past it; 30 s is well within.
TEST(StoryPlan, PlanningPastTheWorkLimitIsRefusedNamingWhere) {
  const model::FlameModel m =
      model::FlameModel::load(std::string(CANDELA_SOURCE_DIR) + "/firmware/models/default.cmodel");
  const std::string head =
      "model = \"x\"\n[[segment]]\nclip = \"" + m.clips.front().name + "\"\n[[segment]]\n";
  const StoryPlan ok = plan_story(load_story_text(head + "arp = 30\n", "t"), m, 1);
  EXPECT_LT(ok.work(), kMaxPlanWork / 2);
  try {
    plan_story(load_story_text(head + "arp = 600\n", "tour.toml"), m, 1);
    FAIL() << "planned";
  } catch (const ConfigError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("tour.toml: segment[1]: expected a story that plans "
                                          "within 400 million component operations",
                                          0),
              0u)
        << e.what();
  }
}

TEST(StoryPlayer, PlaysThePlannedFramesAndLoopsWithoutASeam) {
  const model::FlameModel m = test::two_clip_model();
  const StoryPlan plan =
      plan_story(load_story_text(t1_t2_t2_t1("{ method = \"grow\" }"), "t"), m, 3);
  // 60 animation steps per second, the model's 30 fps: two steps per story frame.
  StoryPlayer player(plan, m.components(), Fixed::from_ratio(1, 2));
  player.set_crossfade(Fixed{});  // hold each frame: the weights are the plan's own
  std::vector<float> gray(m.mean.pixels()), want(m.mean.pixels());
  double worst_pixel = 0;
  const int n = plan.frames();
  for (int step = 1; step <= 2 * n + 6; ++step) {
    player.step();
    const int k = (step / 2) % n;
    ASSERT_EQ(player.frame(), k);
    const auto w = player.weights();
    for (int c = 0; c < m.components(); ++c) ASSERT_EQ(w[c], plan.weights_of(k)[c]) << step;
    if (step % 37 == 0) {  // pixels as candela-tool story reconstructs them
      m.reconstruct(w, gray);
      m.reconstruct({plan.weights_of(k), static_cast<size_t>(plan.components())}, want);
      for (size_t p = 0; p < gray.size(); ++p)
        worst_pixel = std::max(worst_pixel, static_cast<double>(std::fabs(gray[p] - want[p])));
    }
  }
  EXPECT_LT(worst_pixel, 1e-3);
  EXPECT_EQ(player.loops(), 1u);
  // The wrap from the last frame to the first is an ordinary step.
  EXPECT_LE(plan.step_ratio(n - 1), plan.seam_bound());
  // With a crossfade, the weights shown move between neighbours, never past them.
  StoryPlayer fading(plan, m.components(), Fixed::from_ratio(1, 2));
  fading.set_crossfade(Fixed::from_ratio(1, 2));
  for (int step = 0; step < 2 * n; ++step) {
    fading.step();
    const int k = fading.frame();
    const float* a = plan.weights_of(k);
    const float* b = plan.weights_of(k + 1);
    for (int c = 0; c < m.components(); ++c)
      ASSERT_LE(fading.weights()[c], std::max(a[c], b[c]) + 1e-4f);
  }
}

}  // namespace
}  // namespace candela::story
