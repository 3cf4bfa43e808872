#include "app/frame_loop.h"

#include <chrono>
#include <optional>
#include <string>

#include "app/frame_pacing.h"
#include "app/frame_reports.h"
#include "app/kiosk.h"
#include "app/kiosk_post.h"
#include "app/scene_swap.h"
#include "app/screen_watch.h"
#include "app/sd_notify.h"
#include "core/clock.h"
#include "core/log.h"
#include "input/input_hub.h"
#include "sound/sound_output.h"

namespace candela {
namespace {
// What the display delivers: keys go to the inputs, which make them wind
// events like every other input (no InputHub: nowhere).
class KeysToInputs final : public DisplayEvents {
 public:
  explicit KeysToInputs(InputHub* inputs) : inputs_(inputs) {}
  void on_key(Key key) override {
    if (inputs_) inputs_->on_key(key);
  }

 private:
  InputHub* inputs_;
};

// The kiosk's last pass (cross-fade, brightness): the caller's, or made here
// for a kiosk. Null: none (no kiosk, or its program did not build: logged).
KioskPost* kiosk_post(const LoopSettings& s, std::optional<KioskPost>& own) {
  if (!s.kiosk || s.post) return s.post;
  try {
    return &own.emplace();
  } catch (const std::exception& e) {
    LOG_ERROR("kiosk: %s; no brightness or cross-fade", e.what());
    return nullptr;
  }
}

LoopResult run_loop(Display& display, RunningScene scene, const LoopSettings& s) {
  StepClock clock(s.steps_per_second);
  StepContext step;
  step.dt = clock.step_seconds();
  FrameContext frame;
  KeysToInputs keys(s.inputs);
  Kiosk* kiosk = s.kiosk;
  std::optional<KioskPost> own_post;
  KioskPost* post = kiosk_post(s, own_post);
  BrightnessGlide glide{kiosk ? kiosk->target_level() : 1.0f};
  ScreenWatch screen(display, kiosk, s.inputs, s.notify);
  auto do_step = [&] {
    step.step = clock.steps();
    step.time = clock.seconds();
    scene->update(step);
    if (s.sound) {
      SoundCue cue = scene->sound_cue();
      // The `volume` commands' (an atomic), times the schedule's (fades, night).
      if (s.inputs) cue.volume = s.inputs->volume() * (kiosk ? kiosk->volume_level() : 1.0f);
      s.sound->push(cue);
    }
    clock.tick();
  };
  do_step();  // frame 0 shows the state after the first step
  FramePacer pace(display.paced_by_vsync(), s.realtime, s.steps_per_second, s.frames_per_second,
                  s.max_frames);
  FrameReports reports(s.stats, kiosk, s.notify, FramePacer::Clock::now());
  // Frame times for the scene's automatic quality (LoopSettings::time_lockstep_frames).
  const bool timed = !pace.lockstep() || s.time_lockstep_frames;
  LoopResult result;
  while (pace.more()) {
    if (s.stop && s.stop->load(std::memory_order_relaxed)) break;
    if (!display.poll_events(keys)) {
      result.quit_requested = true;
      break;
    }
    if (kiosk && kiosk->scene_waiting()) {
      std::string file;
      if (std::unique_ptr<Scene> next = build_handed_scene(*kiosk, s.seed, s.stop, file)) {
        if (post && screen.screen_on() && display.screen_present() && pace.frames() > 0 &&
            s.crossfade_s > 0 && snapshot_last_frame(display, *post, *scene, frame))
          glide.fade_left_s = static_cast<float>(s.crossfade_s);
        scene.replace(std::move(next));
        do_step();  // the new scene's first state
        if (s.notify) s.notify->set_scene(file);
        kiosk->scene_built({});
      }
    }
    if (!screen.ready(scene->wind(), pace, reports, glide)) continue;
    if (s.inputs) s.inputs->drain(scene->wind());
    const auto begin = FramePacer::Clock::now();
    const FramePacer::Due due = pace.begin_frame(begin, clock);
    for (int i = 0; i < due.steps; ++i) do_step();
    display.begin_frame();
    frame.width = display.width();
    frame.height = display.height();
    frame.frame = pace.frames();
    frame.step = clock.steps() - 1;
    if (s.inputs)
      s.inputs->publish(clock.steps(), pace.frames(), scene->wind().sample(Vec3{}),
                        scene->candles_lit());
    scene->draw(frame);
    if (post) {
      glide.step(due.seconds, kiosk->target_level());
      post->draw(glide.old_alpha(static_cast<float>(s.crossfade_s)), glide.level);
    }
    display.present();
    const auto end = FramePacer::Clock::now();
    if (timed) frame.last_frame_ms = std::chrono::duration<double, std::milli>(end - begin).count();
    reports.presented(pace.frames(), begin, end, frame.width, frame.height);
    pace.end_frame(begin);
  }
  result.frames = pace.frames();
  result.frames_asleep = pace.frames_asleep();
  result.steps = clock.steps();
  return result;
}
}  // namespace

LoopResult run_frame_loop(Display& display, Scene& scene, const LoopSettings& s) {
  return run_loop(display, RunningScene(&scene, nullptr), s);
}

LoopResult run_frame_loop(Display& display, std::unique_ptr<Scene>& scene, const LoopSettings& s) {
  return run_loop(display, RunningScene(scene.get(), &scene), s);
}

}  // namespace candela
