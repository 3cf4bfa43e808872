// Story files (TOML): a model, a sequence of segments (a clip or frame range
// of the model, seconds of Learning Flames ARP synthesis, seconds of the
// graph walk), each with the transition that enters it (the EigenFires
// paper's low-pass, Direct Bridging or End Growing Connection, or a cut), its
// repeats, and a loop back to the start. Read by the runtime's eigenflame
// `story` driver and by `candela-tool story`; validated like scenes: every
// problem is ConfigError(file, key, what was expected).
//
//   model = "builtin:fire"     # a model file (relative to the story) or builtin:fire /
//   builtin:candle seed = 7                   # optional: the walk's and the ARP's choices
//   (default: the element's) loop = true                # the last segment joins the first (through
//   the first's transition) components = 50            # distances (transitions, seams) use the
//   first N EigenFires: the
//                              # paper's ~50 shape weights (beyond them: fine detail, flicker)
//   [[segment]]
//   clip = "fire-calm"         # a clip by name (`candela-tool inspect`), optionally from/to inside
//   it from = 0                   # first frame (of the clip, or of the model without clip) to =
//   120                   # one past the last frame (default: the clip's / model's end) # arp = 4.0
//   # or: seconds of ARP synthesis (models with Learning Flames) # walk = 6.0               # or:
//   seconds of the graph walk repeat = 2                 # played this many times in a row
//   transition = { method = "grow", steps = 20, theta_min = 0, reject_tail = 3 }
//   # method: cut | lowpass (kernel = [a, b, c], components = 50) | bridge (steps = N, 0: auto)
//   #         | grow (steps, theta_min: 0 = half the median step, reject_tail)
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace candela::story {

// Bounds (README: "Stories"): what a story may ask for.
inline constexpr size_t kMaxSegments = 64;
inline constexpr int kMaxRepeat = 100;
inline constexpr double kMaxSegmentSeconds = 600;
inline constexpr int kMaxStoryFrames = 65536;  // planned frames (about 36 min at 30 fps)
inline constexpr int kMaxTransitionSteps = 200;
inline constexpr int kMinSegmentFrames = 4;  // a low-pass joint rewrites two frames at each end

enum class Method { kCut, kLowpass, kBridge, kGrow };
const char* method_name(Method m);

struct TransitionSpec {
  Method method = Method::kGrow;
  std::array<float, 3> kernel{1.0f / 3, 1.0f / 3, 1.0f / 3};  // lowpass taps (T1's side)
  int components = 50;                                        // lowpass: components filtered
  int steps = 20;       // grow: the most steps; bridge: N inserted frames (0: auto, its default)
  float theta_min = 0;  // bridge, grow: smallest step (0: half the model's median step)
  int reject_tail = 3;  // bridge, grow: frames before alpha / after beta never used
  std::string key;      // "segment[2].transition", for messages
};

enum class SegmentKind { kFrames, kArp, kWalk };

struct SegmentSpec {
  SegmentKind kind = SegmentKind::kFrames;
  std::string clip;       // kFrames: a clip name (empty: the model's global frame numbers)
  int from = 0, to = -1;  // kFrames: [from, to) within the clip or model; -1: its end
  double seconds = 0;     // kArp, kWalk
  int repeat = 1;
  TransitionSpec transition;  // how this segment is entered
  std::string key;            // "segment[2]"
};

struct StoryDesc {
  std::string file;   // the story's path (or name), for messages
  std::string model;  // as written: a path relative to the story, or builtin:NAME
  bool has_seed = false;
  uint64_t seed = 1;
  bool loop = true;
  int components = 50;  // distances (transitions, seam ratios) over the first N EigenFires
  std::vector<SegmentSpec> segments;
};

// Throws ConfigError. The file must be a regular file within the scene size limit.
StoryDesc load_story_file(const std::string& path);
StoryDesc load_story_text(std::string_view text, const std::string& name);
// A story by name: "builtin:NAME" (firmware/stories/NAME.toml, embedded), else
// a file, relative to `relative_to`'s folder (a scene file; empty: as given).
StoryDesc open_story(const std::string& name, const std::string& relative_to = {});
// The model as the runtime and the tool open it: "builtin:NAME" unchanged,
// a path resolved against the story file's folder.
std::string story_model_path(const StoryDesc& story);

}  // namespace candela::story
