// A story planned into one cyclic sequence of weight vectors, once, before
// anything plays: the runtime's `story` driver and `candela-tool story` run
// this same code, so the same story and seed give the same frames in both.
//
// Every joint (segment to segment, a segment to its own repeat, and the loop
// from the last segment back to the first) is made by the entered segment's
// transition and measured: its seam ratio is the largest weight-space step
// across the joint divided by the model's median step between consecutive
// frames of a clip (WeightTable::median_step).
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "model/flame_model.h"
#include "story/story_file.h"
#include "story/weight_transitions.h"

namespace candela::story {

// The seam bound: a joint's largest step may be as large as the model's own
// roughest steps (the 99th percentile of its consecutive in-clip steps) and
// never less than twice the median step: a seamless joint moves no faster
// than the footage itself sometimes does. Measured (50 components): the
// built-in fire's steps reach 1.21 median steps at the 99th percentile (its
// hard cuts are 1.5-2.2: its 300 frames are all about equally far apart), the
// built-in candle's 2.80 (its hard cuts: median 5.3, 95th percentile 8.3).
inline constexpr float kMinSeamBound = 2.0f;

// Planning work is bounded, not only the story's size: a story past this many
// component operations (a distance over 50 components is 50; the joints'
// frame searches and the ARP's nearest training states are most of it) is
// refused with a ConfigError naming where planning stopped, so `candela
// --check` refuses it and no kiosk stalls on it. Measured: 5e8 a second on
// one core of the 2-core development machine, so the limit is about 0.8 s
// there (30 s of ARP synthesis on the built-in candle takes 1.7e8; repeats
// are free, their joints are worked out once).
inline constexpr uint64_t kMaxPlanWork = 400'000'000;
inline constexpr double kSeamQuantile = 0.99;

struct JointReport {
  std::string key;   // the transition's key: "segment[1].transition"
  std::string what;  // "segment[0] -> segment[1]", "segment[1] repeat 2", "loop: ..."
  Method method = Method::kCut;
  std::string how;          // what the method did ("bridged", "shared image", ...)
  int alpha = 0, beta = 0;  // model frames: the last before and the first after the joint
  int first = 0, last = 0;  // story frames spanned (last may pass frames(): it wraps)
  int inserted = 0;         // frames a bridge or a grown path put in
  float seam_ratio = 0;     // largest step from `first` to `last` / median step
  float cut_ratio = 0;      // what a hard cut alpha -> beta would have been
};

struct PieceReport {
  std::string key;  // "segment[2]" (+ " repeat 2")
  int first = 0, count = 0;
  float max_step_ratio = 0;  // largest step inside, before any joint touched it
};

class StoryPlan {
 public:
  int frames() const { return static_cast<int>(ref_.size()); }
  int components() const { return stride_; }
  double fps() const { return fps_; }
  bool loop() const { return loop_; }
  float median_step() const { return median_; }
  // The largest seam ratio a joint may have (kMinSeamBound, kSeamQuantile).
  float seam_bound() const { return bound_; }
  // The weights of story frame i (components() floats); i wraps.
  const float* weights_of(int i) const;
  // The model frame story frame i shows, or -1 where a low-pass rewrote it.
  int model_frame(int i) const;
  // Components distances use (the story's `components`, at most the model's).
  int distance_components() const { return dims_; }
  // Step from story frame i to i + 1 (wrapping) in median steps.
  float step_ratio(int i) const;
  const std::vector<JointReport>& joints() const { return joints_; }
  const std::vector<PieceReport>& pieces() const { return pieces_; }
  float worst_seam() const;
  // Component operations planning took (at most kMaxPlanWork).
  uint64_t work() const { return work_; }

 private:
  friend StoryPlan plan_story(const StoryDesc&, const model::FlameModel&, uint64_t, bool);
  std::span<const float> model_weights_;
  int stride_ = 0, dims_ = 0;
  double fps_ = 30;
  bool loop_ = true;
  float median_ = 1, bound_ = kMinSeamBound;
  uint64_t work_ = 0;
  std::vector<int32_t> ref_;  // >= 0: model frame; < 0: row -1 - ref of rows_
  std::vector<float> rows_;
  std::vector<JointReport> joints_;
  std::vector<PieceReport> pieces_;
};

// Throws ConfigError(story file, key, problem) for what the model cannot play
// (an unknown clip, a range outside it, arp without Learning Flames, a story
// longer than kMaxStoryFrames or planning longer than kMaxPlanWork). `force_loop`: plan the loop
// joint even when the story says loop = false (the runtime always loops). The model must outlive
// the plan.
StoryPlan plan_story(const StoryDesc& story, const model::FlameModel& m, uint64_t seed,
                     bool force_loop = false);

}  // namespace candela::story
