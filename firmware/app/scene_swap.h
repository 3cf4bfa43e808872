// A scene swap between two frames (app/frame_loop.cpp): the scene the kiosk
// handed over (a command, the [schedule], a reload) is built on the loop's
// thread, whose GL context its elements need; the running scene's last frame
// is kept for the cross-fade, so no frame is black; a scene that fails to
// build leaves the running one in place.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <string>

#include "scene/scene.h"

namespace candela {

class Display;
class Kiosk;
class KioskPost;

// The running scene: the caller's, or the one a swap brought in. Owning
// (`owner` given), a swap replaces the caller's scene, so the old one's
// memory goes when its cross-fade begins.
class RunningScene {
 public:
  RunningScene(Scene* scene, std::unique_ptr<Scene>* owner) : scene_(scene), owner_(owner) {}
  Scene* operator->() const { return scene_; }
  Scene& operator*() const { return *scene_; }
  void replace(std::unique_ptr<Scene> next);

 private:
  Scene* scene_;
  std::unique_ptr<Scene>* owner_;
  std::unique_ptr<Scene> held_;  // a swapped-in scene when the caller owns none
};

// Builds the scene the kiosk has waiting. Null: none, or it could not be
// built (logged and told to the kiosk; the running scene stays). `file`: its
// file, for systemd's status.
std::unique_ptr<Scene> build_handed_scene(Kiosk& kiosk, uint64_t seed,
                                          const std::atomic<bool>* stop, std::string& file);

// Draws `scene` once more into the cross-fade's snapshot (the frame it last
// showed). False: no snapshot target could be made.
bool snapshot_last_frame(Display& display, KioskPost& post, Scene& scene, FrameContext& frame);

}  // namespace candela
