#include "scene/scene.h"

#include "core/log.h"
#include "core/random.h"
#include "gl/gles.h"

namespace candela {

namespace {
uint64_t element_seed(const SceneDesc& desc, uint64_t seed_override, size_t i) {
  const uint64_t seed = seed_override ? seed_override : desc.seed;
  const ElementSpec& spec = *desc.elements[i].spec;
  return spec.seed ? spec.seed : split_seed(seed, i);
}
}  // namespace

void prepare_scene(SceneDesc& desc, uint64_t seed_override) {
  for (size_t i = 0; i < desc.elements.size(); ++i)
    desc.elements[i].spec->prepare_for(element_seed(desc, seed_override, i));
}

Scene::Scene(const SceneDesc& desc, uint64_t seed_override, const std::atomic<bool>* stop)
    : background_(desc.background),
      camera_(desc.camera),
      wind_(desc.wind),
      scaled_(desc.render_scale, desc.render_max_height) {
  for (size_t i = 0; i < desc.elements.size(); ++i) {
    if (stop && stop->load(std::memory_order_relaxed)) break;  // SIGTERM: do not make the rest
    const auto& e = desc.elements[i];
    SceneContext ctx;
    ctx.scene_file = desc.file;
    ctx.seed = element_seed(desc, seed_override, i);
    ctx.resources = &resources_;
    if (const std::string p = e.spec->problem(); !p.empty())
      LOG_ERROR("%s: %s", desc.file.c_str(), p.c_str());
    try {
      elements_.push_back(e.spec->create(ctx));
    } catch (const std::exception& ex) {
      ++failed_;
      LOG_ERROR("%s: %s: %s; left out of the scene", desc.file.c_str(), e.name.c_str(), ex.what());
    }
  }
}

void Scene::update(const StepContext& step) {
  wind_.update(step);
  StepContext s = step;
  s.wind = &wind_;
  sound_cue_ = SoundCue{};
  for (auto& e : elements_) {
    e->update(s);
    e->add_sound_cue(sound_cue_);
  }
}

void Scene::hash_state(StateHash& hash) const {
  const WindSample w = wind_.sample(Vec3{});
  hash.add(w.x);
  hash.add(w.z);
  hash.add(sound_cue_.fire);
  hash.add(sound_cue_.activity);
  hash.add(sound_cue_.wind);
  hash.add(uint32_t{sound_cue_.blowouts});
  hash.add(uint32_t{sound_cue_.sputters});
  hash.add(uint32_t{sound_cue_.lit});
  hash.add(static_cast<uint64_t>(elements_.size()));
  for (const auto& e : elements_) e->hash_state(hash);
}

void Scene::draw(FrameContext& frame) {
  const float aspect = frame.height > 0 ? static_cast<float>(frame.width) / frame.height : 1.0f;
  frame.view = Mat4::look_at(camera_.position, camera_.target, {0, 1, 0});
  frame.projection =
      Mat4::perspective(camera_.fov_deg * 3.14159265f / 180.0f, aspect, 0.02f, 100.0f);
  frame.view_projection = frame.projection * frame.view;
  frame.camera_position = camera_.position;
  // The framebuffer the display bound for this frame.
  GLint screen = 0;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &screen);
  frame.screen_framebuffer = static_cast<uint32_t>(screen);
  // Drawn at a reduced size: the elements see the reduced target as their
  // screen, and it is scaled up onto the real one at the end.
  const RenderSize full{frame.width, frame.height};
  const RenderSize drawn = scaled_.size_for(full);
  if (drawn != full) {
    frame.screen_framebuffer = scaled_.begin(drawn);
    frame.width = drawn.width;
    frame.height = drawn.height;
  }
  // 1. Offscreen work, 2. the screen, 3. the passes (scene/element.h).
  for (auto& e : elements_) e->prepare(frame);
  resources_.prepare(frame);
  // Drawn at a reduced size, only where the elements can draw is scaled up
  // (each says where, or that it cannot: then all of it).
  PixelBox content{0, 0, frame.width, frame.height};
  if (drawn != full) {
    Box3 box;
    bool bounded = !scale_up_whole_;
    for (const auto& e : elements_) bounded = bounded && e->drawn_bounds(frame, box);
    if (!bounded || !project_box(box, frame.view_projection, drawn, content))
      content = {0, 0, frame.width, frame.height};
  }
  glBindFramebuffer(GL_FRAMEBUFFER, frame.screen_framebuffer);
  glViewport(0, 0, frame.width, frame.height);
  glDisable(GL_SCISSOR_TEST);
  glClearColor(background_.x, background_.y, background_.z, 1.0f);
  // Stencil too, though nothing uses it: a depth buffer that shares its words with
  // stencil bits (D24S8) then clears in whole words, not by a read-modify-write of
  // each (on llvmpipe the masked clear was two thirds of an empty frame at 1080p).
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
  for (DrawPass pass : kAllPasses)
    for (auto& e : elements_) e->draw(frame, pass);
  if (drawn != full) {
    frame.screen_framebuffer = static_cast<uint32_t>(screen);
    frame.width = full.width;
    frame.height = full.height;
    glBindFramebuffer(GL_FRAMEBUFFER, frame.screen_framebuffer);
    glViewport(0, 0, full.width, full.height);
    scaled_.finish(full, content, background_);
  }
}

int Scene::candles_lit() const {
  int lit = -1;
  for (const auto& e : elements_)
    if (const int n = e->candles_lit(); n >= 0) lit = (lit < 0 ? 0 : lit) + n;
  return lit;
}

}  // namespace candela
