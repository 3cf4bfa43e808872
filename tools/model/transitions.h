// Motion transitions between two frames in EigenFire weight space
// (Nikfetrat & Lee): low-pass blending, Direct Bridging, End Growing
// Connection, over Eigen matrices: each the firmware's planner
// (story/weight_transitions.h, one implementation for the device and the
// tools); and the motion graph built from the same distances.
#pragma once

#include <Eigen/Dense>
#include <string>
#include <vector>

#include "model/flame_model.h"

namespace candela::tools {

// Weight vectors of the frames (rows), first `components` columns used for distances.
struct WeightSpace {
  Eigen::MatrixXf w;         // frames x E
  std::vector<int> clip_of;  // frame -> clip index (for "frames before alpha / after beta")
  std::vector<int> clip_first, clip_end;
  std::vector<model::ClipInfo> clips;
  Eigen::MatrixXf cols;  // E x frames: the same, one contiguous column per frame
  float distance(int a, int b) const { return (cols.col(a) - cols.col(b)).norm(); }
  int frames() const { return static_cast<int>(w.rows()); }
  static WeightSpace from(const Eigen::MatrixXf& weights, const std::vector<model::ClipInfo>& clips,
                          int components = 0);
};

// Low-pass transition: the weights of T1 (its frames in order) then T2 are
// filtered with `kernel` (3 taps, centred; flipped for T2's side) over the
// first `filtered` components; returns the new weights of the last two frames
// of T1 and the first two of T2 (4 rows), the other components unchanged.
Eigen::MatrixXf lowpass_transition(const Eigen::MatrixXf& weights, const std::vector<int>& t1,
                                   const std::vector<int>& t2, const std::vector<float>& kernel,
                                   int filtered = 50);

struct TransitionOptions {
  int steps = 20;       // N
  float theta_min = 0;  // smallest step allowed (below it looks like slow motion)
  int reject_tail = 3;  // frames just before alpha / just after beta are not used
};

struct Transition {
  bool found = false;
  std::string how;        // "shared image", "gap below theta_min", "bridged", or why it failed
  std::vector<int> path;  // alpha, the inserted frames, beta
};

Transition direct_bridging(const WeightSpace& s, int alpha, int beta, const TransitionOptions& o);
Transition end_growing(const WeightSpace& s, int alpha, int beta, const TransitionOptions& o);
// Drops frames that make a detour or a step below theta_min (Table 1's Optimize_Path).
void optimise_path(const WeightSpace& s, std::vector<int>& path, float theta_min);

struct MotionGraphOptions {
  float theta_min = 0;            // <= 0: half the median step between consecutive frames
  int max_successors = 4;         // jumps per frame besides the next frame
  int min_jump = 12;              // a jump lands at least this many frames away (same clip)
  float max_step_factor = 1.25f;  // a jump is at most this x the median natural step
};
struct MotionGraphData {
  std::vector<int32_t> offsets, successors;
  std::vector<float> cost;
  float theta_min = 0;
  float median_step = 0;
};
// For every frame: the next frame of its clip (if any) and the best jumps: frames
// that look like the natural next frame and are a step in [theta_min, max step]
// away. Every frame gets at least one successor, so a walk never ends.
MotionGraphData build_motion_graph(const WeightSpace& s, const MotionGraphOptions& o);

}  // namespace candela::tools
