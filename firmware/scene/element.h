// The scene-element interface. An element is one thing in the scene (a
// candle, an eigen-flame, a Perlin fire, the test pattern). It is parsed and
// validated without GL (ElementSpec, used by --check), then created with GL.
// update() runs on the fixed animation step; prepare() and draw() issue GL
// calls only. None may allocate once running.
//
// A frame, as Scene::draw() runs it:
//   1. prepare(frame) on every element, then prepare(frame) on every shared
//      resource (SceneResources) the elements made;
//   2. the scene binds the screen framebuffer (frame.screen_framebuffer) with
//      the whole screen as viewport and the scissor test off, and clears it;
//   3. draw(frame, pass) on every element, pass by pass (DrawPass).
// The rule: offscreen work happens in prepare; draw passes only draw into
// the bound screen framebuffer. Anything that binds another framebuffer,
// changes the viewport or renders into a texture (an eigen-flame's
// reconstruction, a Perlin fire's reduced-scale march, a cached background)
// goes in prepare, which may leave any framebuffer bound; filling and
// uploading per-frame instance buffers goes there too. A draw pass leaves
// the screen framebuffer bound and the viewport as it found them, so the
// screen is entered once per frame (on tiled GPUs and llvmpipe each re-entry
// stores and reloads the whole screen).
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <typeinfo>
#include <vector>

#include "core/fixed.h"
#include "core/state_hash.h"
#include "gl/math.h"
#include "sound/sound_cue.h"
#include "wind/step_context.h"

namespace candela {

class WindField;
class ParamReader;

// Elements draw in passes, so that (as the candle paper asks) every glow is
// drawn before any candle body or flame.
enum class DrawPass { kBackground, kGlow, kBody, kFlame, kOverlay };
inline constexpr DrawPass kAllPasses[] = {DrawPass::kBackground, DrawPass::kGlow, DrawPass::kBody,
                                          DrawPass::kFlame, DrawPass::kOverlay};

struct FrameContext {
  int width = 0, height = 0;
  uint64_t frame = 0;  // frames presented so far
  uint64_t step = 0;   // the animation step being shown
  Mat4 view, projection, view_projection;
  Vec3 camera_position;
  double last_frame_ms = 0;  // the previous frame's time, begin to end of present (0: none yet)
  // The framebuffer the draw passes draw into (a GL name; 0: the window's):
  // the one bound when Scene::draw() began. Set before prepare().
  uint32_t screen_framebuffer = 0;
};

// Something the elements of one scene share (the atlases every eigen-flame
// renders into). Made on first use, it lives as long as the scene, longer
// than any element; its prepare() runs once per frame, after every
// element's prepare() (the same rule: offscreen work only).
class SceneResource {
 public:
  virtual ~SceneResource() = default;
  virtual void prepare(const FrameContext& /*frame*/) {}
};

// The scene's shared resources, one of each type. Elements ask for theirs at
// creation (ElementSpec::create) and keep the reference.
class SceneResources {
 public:
  // The scene's T (a SceneResource made with T(), GL context current),
  // made now if this is the first asking.
  template <class T>
  T& get() {
    static_assert(std::is_base_of_v<SceneResource, T>);
    for (const auto& r : resources_)
      if (*r.type == typeid(T)) return static_cast<T&>(*r.resource);
    resources_.push_back({&typeid(T), std::make_unique<T>()});
    return static_cast<T&>(*resources_.back().resource);
  }
  void prepare(const FrameContext& frame) {
    for (const auto& r : resources_) r.resource->prepare(frame);
  }

 private:
  struct Entry {
    const std::type_info* type;
    std::unique_ptr<SceneResource> resource;
  };
  std::vector<Entry> resources_;
};

struct SceneContext {
  std::string scene_file;  // for messages and relative paths
  uint64_t seed = 1;       // this element's seed (scene seed mixed with its index, or its own)
  SceneResources* resources = nullptr;  // the scene's; never null when a Scene creates elements
};

class Element {
 public:
  virtual ~Element() = default;
  virtual void update(const StepContext& step) = 0;
  // This frame's offscreen work (see the rule above); called once per frame
  // before the screen is cleared. Default: none.
  virtual void prepare(const FrameContext& /*frame*/) {}
  // Draws this pass into the bound screen framebuffer, and nothing else.
  virtual void draw(const FrameContext& frame, DrawPass pass) = 0;
  // Where this frame's draw passes can put light: `box` (world space) is
  // grown to hold everything the element draws on the screen this frame,
  // glows, halos and what it lights included. Called after prepare(), before
  // the draw passes; a scene drawn at a reduced size scales up only the part
  // of the picture its elements' boxes cover (scene/scaled_render.h), so a
  // box too small cuts the picture. Returns false where the element cannot
  // say (then the whole screen is scaled up); the default.
  virtual bool drawn_bounds(const FrameContext& /*frame*/, Box3& /*box*/) const { return false; }
  // How many candles this element shows alight (the control socket's
  // `state`); -1: it has no candles. Called once per frame: no allocation.
  virtual int candles_lit() const { return -1; }
  // What this step sounds like (sound/sound_cue.h). The scene calls it once
  // per animation step, right after this element's update(), with one cue
  // it cleared before the step and shares among all elements: add to it
  // (fire, activity, counts) or raise it (wind); never clear it. Called
  // whether or not the scene plays sound; no allocation, no GL. Default: silent.
  virtual void add_sound_cue(SoundCue& /*cue*/) const {}
  // Feeds this element's animation state (what update() changes: its
  // fixed-point values and what it derives from them for drawing) to `hash`.
  // For checking that two builds animate alike (tests/arm64); never called
  // by the frame loop. Default: no state.
  virtual void hash_state(StateHash& /*hash*/) const {}
};

class ElementSpec {
 public:
  virtual ~ElementSpec() = default;
  // Needs a current GL context. Throws on failure; the scene logs it and
  // carries on without (or with a fallback for) this element.
  virtual std::unique_ptr<Element> create(const SceneContext& context) const = 0;
  // Something the scene names that cannot be used, though the element will
  // run with a fallback (an eigen-flame's broken model): logged at start-up,
  // an error for `candela --check`. Empty: nothing wrong.
  virtual std::string problem() const { return {}; }
  // Memory and GPU cost in units of a typical element (the test pattern, a
  // group of up to 512 candles: 1; an eigen-flame with its textures and
  // buffers: 4); a scene may spend kMaxElementCost (scene/scene_file.h).
  virtual unsigned cost() const { return 1; }
  // Work without GL that depends on the element's seed (an eigen-flame's
  // story plan), done where the scene is read, off the frame loop: create()
  // with the same seed then finds it done. Called once, before the spec is
  // handed to the thread that creates the element (prepare_scene).
  virtual void prepare_for(uint64_t element_seed) { (void)element_seed; }
  Vec3 position;
  uint64_t seed = 0;  // 0: derived from the scene's seed
};

struct ElementKind {
  std::string_view name;
  std::string_view summary;
  // Reads and validates this kind's parameters (position and seed are read
  // by the scene); calls reader.finish() itself.
  std::unique_ptr<ElementSpec> (*parse)(ParamReader& reader);
};

// Every kind the runtime knows (elements/element_kinds.cpp).
std::span<const ElementKind> element_kinds();

}  // namespace candela
