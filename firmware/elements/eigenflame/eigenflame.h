// The "eigenflame" scene element: a flame played from a model built by
// `candela-tool build` (EigenFires PCA + motion graph, optionally a Learning
// Flames ARP), reconstructed on the GPU every frame.
//
//   [[element]]
//   kind = "eigenflame"
//   model = "flames.cmodel"    # relative to the scene, or builtin:candle / builtin:fire
//                              # (embedded); default: the built-in default model
//   position = [0, 0, 0]       # bottom centre of the flame image, world metres
//   height = 0.5               # world height of the flame image
//   widen = 1.0                # graph driver: stretch the image sideways (a broader fire)
//   driver = "graph"           # graph (EigenFires walk) | arp (Learning Flames) | story
//   story = "tour.toml"        # a story file (firmware/story/story_file.h; relative to the
//                              # scene, or builtin:NAME): its segments and transitions, planned
//                              # at start-up and looped; implies driver = "story"; the story
//                              # names the model (no `model` key then)
//   seed = 7                   # optional; default from the scene's seed
//   components = 0             # use the first N components (0: all the model has)
//   layout = "packed"          # packed (4 per texel) | layered (1 per array layer)
//   speed = 1.0                # playback speed (model frames at the model's fps)
//   crossfade = 0.25           # share of each model frame spent fading into the next:
//                              # 0 holds each frame as a video player does, 1 blends all the
//                              # way (soft, ghosted tongues); a little hides the steps
//   hue = 28                   # HLS colour: gray is the lightness (defaults: the model's)
//   hue_top = 50               # the hue at full brightness (default: hue); it moves there
//                              # with the cube of the gray: deep orange edges, yellow core
//   saturation = 0.9
//   transfer = "#000000 #8a1800 #ff8020 #fff0c0"  # or a transfer function (even stops)
//   transfer = "#000000@0 #8a1800@0.2 #ff8020@0.5 #fff0c0@1"  # or stops at chosen places
//                              # (all or none placed; 0..1 of the gray, rising)
//   weight_offsets = [0, 0, 1.5]  # graph/story drivers: weight k moved by this many standard
//                              # deviations of weight k over the model's frames (at most 50
//                              # entries, each -5..5; the studio's weight sliders)
//   detail_scale = 1.0         # 0..4: scales the weights from 50 on (the fine detail)
//   brightness = 1.0
//   flicker = 0.0              # 0..1: the flame's light flickers as firelight does (core/
//                              # flicker.h, 0.7-11 Hz) by this share of its swing: a
//                              # simulation's light changes too slowly (its brightness
//                              # spectrum is steeper than a real fire's)
//   glow_radius = 0.12         # fraction of the flame height (default: the model's)
//   glow_strength = 0.6
//   edge_fade = 0.05           # fade the flame out over this share of the image at its
//                              # sides and top (where a wide fire or clipped footage ends)
//   foot_fade = [0.25, 0.45]   # fade the image's foot in between these heights (0 bottom,
//                              # 1 top): hides a model's own bed and logs where a scene
//                              # has its own (default none)
//   in_front = true            # drawn after the other elements' front parts (a hearth's
//                              # front logs; the overlay pass): flames licking up in front
//                              # of them, as in footage (default false: behind them)
//   [element.graph]  max_stretch = 45  window = 1800  jump_chance = 0.08  steer_chance = 0.17
//   [element.wind]   lean = 0.05  max_lean = 0.2  response = 2.0  bend = 0.15
//   [element.embers] width = 0.6  depth = 0.25  colour = "#ff5010"  # a glowing bed under it
//
// A model that cannot be loaded is reported (file, key, what is wrong) when
// the scene is read (also by `candela --check`) and the element plays the
// built-in default model instead, so the display never goes dark. So does a
// story that cannot be read or planned (its graph walk plays instead).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/fixed.h"
#include "elements/eigenflame/eigen_renderer.h"
#include "flame_drivers/graph_walker.h"
#include "flame_drivers/weight_edits.h"
#include "gl/math.h"
#include "scene/element.h"
#include "story/story_file.h"
#include "story/story_plan.h"

namespace candela {

namespace model {
class FlameModel;
}

// A loaded model plus what the runtime derives from it once (per-frame lean).
struct EigenModel {
  std::shared_ptr<const model::FlameModel> model;
  std::string source;        // path, or "<built-in default>"
  std::vector<Fixed> lean;   // per frame: centroid x relative to the calm lean, image widths
  std::vector<float> sigma;  // per weight: its standard deviation over the frames (weight_sigmas)
};

// The built-in model (firmware/models/default.cmodel, embedded); loaded once.
std::shared_ptr<const EigenModel> default_eigen_model();
// A built-in model by name ("default", "candle", "fire": firmware/models/
// NAME.cmodel, embedded); loaded once. Throws ConfigError for an unknown name.
std::shared_ptr<const EigenModel> builtin_eigen_model(const std::string& name);
// Loads and validates a model file; throws model::ModelError / ConfigError.
std::shared_ptr<const EigenModel> load_eigen_model(const std::string& path);

enum class EigenDriver { kGraph, kArp, kStory };

struct EigenEmbers {
  bool enabled = false;
  float width = 0.6f, depth = 0.25f;
  Vec3 colour{1.0f, 0.32f, 0.06f};
};

struct EigenFlameSettings {
  float height = 0.5f;
  float widen = 1.0f;  // graph driver: stretches the image sideways
  EigenDriver driver = EigenDriver::kGraph;
  int components = 0;
  StackLayout layout = StackLayout::kPacked;
  Fixed speed = Fixed::from_int(1);
  Fixed crossfade = Fixed::from_ratio(1, 4);
  bool has_hue = false, has_hue_top = false, has_saturation = false, has_glow_radius = false,
       has_glow_strength = false;
  float hue = 28, hue_top = 28, saturation = 0.9f;
  std::vector<Vec3> transfer;      // non-empty: overrides HLS
  std::vector<float> transfer_at;  // empty: evenly spaced; else each stop's place (0..1)
  float brightness = 1.0f;
  Fixed flicker;  // 0..1, share of core/flicker.h's swing
  float glow_radius = 0.12f, glow_strength = 0.6f;
  float edge_fade = 0.05f;
  float foot_fade[2] = {0, 0};  // image heights: hidden below the first, whole above the second
  bool in_front = false;        // drawn in the overlay pass, over a hearth's front logs
  EigenWeightEdits weights;  // weight_offsets, detail_scale (graph and story drivers)
  WalkSettings walk;
  Fixed wind_lean = Fixed::from_ratio(5, 100);   // target lean per m/s, image widths
  Fixed max_lean = Fixed::from_ratio(20, 100);   // image widths
  Fixed lean_response = Fixed::from_int(2);      // 1/s
  Fixed wind_bend = Fixed::from_ratio(15, 100);  // arp: path offset at the tip per m/s, heights
  EigenEmbers embers;
};

class EigenFlameSpec final : public ElementSpec {
 public:
  std::unique_ptr<Element> create(const SceneContext& context) const override;
  std::string problem() const override;              // model_error: --check fails on it
  void prepare_for(uint64_t element_seed) override;  // the story planned for that seed
  unsigned cost() const override { return 4; }
  EigenFlameSettings settings;
  std::shared_ptr<const EigenModel> model;  // never null: the default if the named one failed
  std::string model_error;                  // why the named model was not used (empty: it was)
  std::shared_ptr<const story::StoryDesc> story;  // driver kStory: read and planned once already
  // The plan made while parsing (with story_plan_seed): create() plays it
  // where the element's seed gives the same plan, rather than planning again.
  std::shared_ptr<const story::StoryPlan> story_plan;
  uint64_t story_plan_seed = 0;
  std::string story_error;  // why the named story is not played
};

std::unique_ptr<EigenFlameSpec> parse_eigenflame(ParamReader& reader);
const ElementKind& eigenflame_kind();

}  // namespace candela
