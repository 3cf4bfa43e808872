// The running scene: elements made from a SceneDesc, the wind field and the
// resources they share, and the camera. The frame loop calls update() per
// fixed step and draw() per frame (the order of a frame: scene/element.h).
// Its wind hears keys, sensors and the control socket through input/InputHub.
#pragma once

#include <atomic>
#include <memory>
#include <vector>

#include "scene/element.h"
#include "scene/scaled_render.h"
#include "scene/scene_file.h"
#include "wind/wind_field.h"

namespace candela {

// Each element's GL-free work for the seed it will be created with (the same
// `seed_override` as Scene's; ElementSpec::prepare_for): on the thread that
// read the scene, so the frame loop only creates what is ready.
void prepare_scene(SceneDesc& desc, uint64_t seed_override = 0);

class Scene {
 public:
  // Needs a current GL context. An element that fails to create is logged and
  // left out: the display never goes dark because of one bad element.
  // `stop`, when set (a signal), ends the building early: the scene then has
  // the elements made so far.
  Scene(const SceneDesc& desc, uint64_t seed_override = 0, const std::atomic<bool>* stop = nullptr);
  void update(const StepContext& step);
  void draw(FrameContext& frame);

  WindField& wind() { return wind_; }
  size_t element_count() const { return elements_.size(); }
  size_t failed_elements() const { return failed_; }
  // Candles alight over all elements; -1 if no element has candles.
  int candles_lit() const;
  // What the last update() sounded like: every element's add_sound_cue().
  const SoundCue& sound_cue() const { return sound_cue_; }
  // Feeds the animation state after the last update() -- the wind at the
  // origin, the sound cue and every element's hash_state() -- to `hash`
  // (tests/arm64 compares builds with it). Not for the frame loop.
  void hash_state(StateHash& hash) const;
  // Drawn at a reduced size: the screen pixels the last draw() scaled up
  // (the rest it cleared to the background). Tests compare it against
  // scaling up everything (`scale_up_whole`), as when no element says where
  // it draws.
  PixelBox last_scaled_up() const { return scaled_.last_scaled_up(); }
  void scale_up_whole(bool whole) { scale_up_whole_ = whole; }

 private:
  Vec3 background_;
  CameraDesc camera_;
  WindField wind_;
  ScaledRender scaled_;  // [display] render_scale / render_max_height
  bool scale_up_whole_ = false;
  SceneResources resources_;  // before elements_: outlives every element
  std::vector<std::unique_ptr<Element>> elements_;
  size_t failed_ = 0;
  SoundCue sound_cue_;
};

}  // namespace candela
