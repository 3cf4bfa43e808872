// The frame loop. It knows a Display and a Scene, never which backend it has.
// Animation advances on the fixed-step clock: in lockstep with frames where
// nothing paces presentation (headless: deterministic output), by wall time
// where vsync does.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>

#include "app/frame_stats.h"
#include "display/display.h"
#include "scene/scene.h"

namespace candela {

class InputHub;
class Kiosk;
class KioskPost;
class SdNotify;
class SoundOutput;

struct LoopSettings {
  // 0: until quit. Frame periods with nothing shown (screen off, no
  // monitor) count too, so a bounded run ends whatever its schedule does.
  uint64_t max_frames = 0;
  int steps_per_second = 60;
  int frames_per_second = 60;  // lockstep: steps per frame = steps_per_second / fps
  // Where nothing paces presentation (headless), hold frames_per_second by
  // wall clock and advance animation by wall time, like a live display
  // (for automation through the control socket). Off: lockstep, as fast as
  // frames can be drawn (deterministic recordings, --bench).
  bool realtime = false;
  // Each frame's time reaches the scene (FrameContext::last_frame_ms: the
  // Perlin fire's automatic quality holds its frame rate by it) only where
  // animation runs in real time (vsync or `realtime`): a lockstep run (a
  // recording, --bench) has no frame rate to hold, so it draws every frame at
  // the scene's own quality, the same on any machine. On: in lockstep too
  // (tests of automatic quality).
  bool time_lockstep_frames = false;
  const std::atomic<bool>* stop = nullptr;  // set by a signal handler
  FrameStats* stats = nullptr;
  InputHub* inputs = nullptr;    // sensors, camera, control socket: drained once per frame
  SdNotify* notify = nullptr;    // systemd READY/WATCHDOG/STATUS after presented frames
  SoundOutput* sound = nullptr;  // gets every step's Scene::sound_cue() (sound/sound_output.h)
  // Live control (app/kiosk.h): scene swaps, brightness, screen off. Null:
  // none (the loop then draws exactly what it always did).
  Kiosk* kiosk = nullptr;
  uint64_t seed = 0;  // --seed, for scenes the kiosk swaps in (0: each scene's own)
  double crossfade_s = 1.0;
  KioskPost* post = nullptr;  // app/kiosk_post.h; null: the loop makes its own (with a kiosk)  // a
                              // scene swap's cross-fade from the old scene's last frame
};

struct LoopResult {
  uint64_t frames = 0;         // drawn and presented
  uint64_t frames_asleep = 0;  // frame periods passed with the screen off or absent
  uint64_t steps = 0;
  bool quit_requested = false;
};

LoopResult run_frame_loop(Display& display, Scene& scene, const LoopSettings& settings);
// As above, owning the scene: a swap (LoopSettings::kiosk) replaces it, so
// the old one's memory goes when its cross-fade begins.
LoopResult run_frame_loop(Display& display, std::unique_ptr<Scene>& scene,
                          const LoopSettings& settings);

}  // namespace candela
