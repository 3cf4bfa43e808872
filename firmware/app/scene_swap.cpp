#include "app/scene_swap.h"

#include "app/kiosk.h"
#include "app/kiosk_post.h"
#include "core/log.h"
#include "display/display.h"

namespace candela {

void RunningScene::replace(std::unique_ptr<Scene> next) {
  if (owner_)
    *owner_ = std::move(next), scene_ = owner_->get();
  else
    held_ = std::move(next), scene_ = held_.get();
}

std::unique_ptr<Scene> build_handed_scene(Kiosk& kiosk, uint64_t seed,
                                          const std::atomic<bool>* stop, std::string& file) {
  std::unique_ptr<SceneDesc> desc = kiosk.take_scene();
  if (!desc) return nullptr;
  std::unique_ptr<Scene> next;
  std::string error;
  try {
    next = std::make_unique<Scene>(*desc, seed, stop);
    if (next->element_count() == 0) error = desc->file + ": no element could be created";
  } catch (const std::exception& e) {
    error = desc->file + ": " + e.what();
  }
  if (!error.empty()) {
    LOG_ERROR("scene: %s; the running scene stays", error.c_str());
    kiosk.scene_built(error);
    return nullptr;
  }
  file = desc->file;
  return next;
}

bool snapshot_last_frame(Display& display, KioskPost& post, Scene& scene, FrameContext& frame) {
  display.begin_frame();
  frame.width = display.width();
  frame.height = display.height();
  RenderTarget& old = post.snapshot_target(frame.width, frame.height);
  if (!old.complete()) return false;
  old.bind();
  scene.draw(frame);  // the old scene, as it was last shown
  return true;
}

}  // namespace candela
