#include "app/frame_loop.h"

#include <algorithm>
#include <chrono>
#include <optional>
#include <thread>

#include "app/kiosk.h"
#include "app/kiosk_post.h"
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

LoopResult run_loop(Display& display, Scene* scene_in, std::unique_ptr<Scene>* owner,
                    const LoopSettings& s) {
  using Clock = std::chrono::steady_clock;
  StepClock clock(s.steps_per_second);
  const bool lockstep = !display.paced_by_vsync() && !s.realtime;
  const bool self_paced = !display.paced_by_vsync() && s.realtime;
  const int fps = s.frames_per_second > 0 ? s.frames_per_second : 60;
  const auto frame_period = std::chrono::nanoseconds(1'000'000'000LL / fps);
  const int steps_per_frame = std::max(1, s.steps_per_second / fps);
  LoopResult result;
  StepContext step;
  step.dt = clock.step_seconds();
  FrameContext frame;
  KeysToInputs keys(s.inputs);
  Scene* scene = scene_in;
  std::unique_ptr<Scene> held;  // a swapped-in scene when the caller owns none
  Kiosk* kiosk = s.kiosk;
  std::optional<KioskPost> own_post;
  KioskPost* post = s.post;
  if (kiosk && !post) {
    try {
      post = &own_post.emplace();
    } catch (const std::exception& e) {
      LOG_ERROR("kiosk: %s; no brightness or cross-fade", e.what());
    }
  }
  float level = kiosk ? kiosk->target_level() : 1.0f;  // the brightness shown, gliding
  float fade_left_s = 0.0f;                            // of the cross-fade
  bool screen_on = true;
  bool screen_present = true;    // the display has somewhere to show frames
  int shown_w = 0, shown_h = 0;  // the size the kiosk was last told frames are drawn at
  uint64_t fps_frames = 0;
  auto fps_since = Clock::now();
  // With --frames, the frame periods that pass with nothing shown (screen
  // off, no monitor) count toward max_frames, so a bounded run ends although
  // its schedule keeps the screen dark. Counted from when the sleep began.
  std::optional<Clock::time_point> asleep_since;
  auto count_asleep = [&] {
    const auto now = Clock::now();
    if (!asleep_since) {
      asleep_since = now;
      return;
    }
    const int64_t periods = (now - *asleep_since) / frame_period;
    result.frames_asleep += static_cast<uint64_t>(periods);
    *asleep_since += periods * frame_period;
  };
  // The longest a sleep may last: a quarter second, less when --frames ends sooner.
  auto sleep_ms = [&] {
    if (s.max_frames == 0) return 250;
    const uint64_t left =
        s.max_frames - std::min(s.max_frames, result.frames + result.frames_asleep);
    const int64_t periods = static_cast<int64_t>(std::min<uint64_t>(left, 1'000'000));
    const auto left_ms = std::chrono::ceil<std::chrono::milliseconds>(periods * frame_period);
    return static_cast<int>(std::clamp<int64_t>(left_ms.count(), 1, 250));
  };

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
  // A scene the kiosk hands over: built here (its GL work needs this
  // thread's context), between two frames; the old one's last frame is
  // kept for the cross-fade, so no frame is black.
  auto swap_scene = [&] {
    std::unique_ptr<SceneDesc> desc = kiosk->take_scene();
    if (!desc) return;
    std::unique_ptr<Scene> next;
    std::string error;
    try {
      next = std::make_unique<Scene>(*desc, s.seed, s.stop);
      if (next->element_count() == 0) error = desc->file + ": no element could be created";
    } catch (const std::exception& e) {
      error = desc->file + ": " + e.what();
    }
    if (!error.empty()) {
      LOG_ERROR("scene: %s; the running scene stays", error.c_str());
      kiosk->scene_built(error);
      return;
    }
    if (post && screen_on && display.screen_present() && result.frames > 0 && s.crossfade_s > 0) {
      display.begin_frame();
      frame.width = display.width();
      frame.height = display.height();
      RenderTarget& old = post->snapshot_target(frame.width, frame.height);
      if (old.complete()) {
        old.bind();
        scene->draw(frame);  // the old scene, as it was last shown
        fade_left_s = static_cast<float>(s.crossfade_s);
      }
    }
    if (owner)
      *owner = std::move(next), scene = owner->get();
    else
      held = std::move(next), scene = held.get();
    do_step();  // the new scene's first state
    if (s.notify) s.notify->set_scene(desc->file);
    kiosk->scene_built({});
  };
  // Frame 0 shows the state after the first step.
  do_step();
  auto last_present = Clock::now();
  auto prev_begin = last_present;
  while (s.max_frames == 0 || result.frames + result.frames_asleep < s.max_frames) {
    if (s.stop && s.stop->load(std::memory_order_relaxed)) break;
    if (!display.poll_events(keys)) {
      result.quit_requested = true;
      break;
    }
    if (kiosk) {
      if (kiosk->scene_waiting()) swap_scene();
      if (kiosk->screen_on() != screen_on) {
        screen_on = !screen_on;
        display.set_screen_power(screen_on);
        fps_frames = 0;
        fps_since = Clock::now();
        if (screen_on) {
          prev_begin = Clock::now();  // no catching up on the time spent off
          level = 0.0f;               // glides up from black
        } else {
          kiosk->set_fps(0.0f);
        }
      }
      if (!screen_on) {
        // Nothing drawn or presented, the animation paused: asleep until a
        // command wakes it (or a quarter second, for signals and pings).
        if (s.inputs) s.inputs->drain(scene->wind());
        if (s.notify) s.notify->idle(Clock::now());
        count_asleep();
        kiosk->wait_for_wake(sleep_ms());
        count_asleep();
        continue;
      }
    }
    if (!display.screen_present()) {
      // No monitor (DRM hot-plug): nothing drawn, the animation paused, the
      // loop alive (watchdog pings) and waiting on the display's uevents.
      if (s.inputs) s.inputs->drain(scene->wind());
      if (s.notify) s.notify->idle(Clock::now(), "waiting for a screen");
      if (kiosk && screen_present) {
        kiosk->set_fps(0.0f);
        kiosk->set_output(Kiosk::Output::kWaiting, shown_w, shown_h);
      }
      screen_present = false;
      shown_w = shown_h = 0;  // told again once a screen is there
      count_asleep();
      display.wait_for_screen(sleep_ms());
      count_asleep();
      continue;
    }
    asleep_since.reset();
    if (!screen_present) {  // a screen again: no catching up on the time without one
      screen_present = true;
      prev_begin = Clock::now();
      fps_frames = 0;
      fps_since = prev_begin;
    }
    if (s.inputs) s.inputs->drain(scene->wind());
    const auto begin = Clock::now();
    const double since_ms = std::chrono::duration<double, std::milli>(begin - prev_begin).count();
    if (result.frames > 0) {
      const int due =
          lockstep ? steps_per_frame
                   : clock.advance_wall(
                         std::chrono::duration_cast<std::chrono::nanoseconds>(begin - prev_begin)
                             .count());
      for (int i = 0; i < due; ++i) do_step();
    }
    prev_begin = begin;
    display.begin_frame();
    frame.width = display.width();
    frame.height = display.height();
    frame.frame = result.frames;
    frame.step = clock.steps() - 1;
    if (s.inputs)
      s.inputs->publish(clock.steps(), result.frames, scene->wind().sample(Vec3{}),
                        scene->candles_lit());
    scene->draw(frame);
    if (post) {
      // The glide: the whole range in a quarter second (no flash, no lag).
      const float dt = lockstep ? 1.0f / static_cast<float>(fps)
                                : static_cast<float>(std::min(since_ms, 250.0) / 1000.0);
      const float target = kiosk->target_level();
      level += std::clamp(target - level, -4.0f * dt, 4.0f * dt);
      fade_left_s = std::max(0.0f, fade_left_s - dt);
      post->draw(s.crossfade_s > 0 ? fade_left_s / static_cast<float>(s.crossfade_s) : 0.0f, level);
    }
    display.present();
    const auto end = Clock::now();
    const double work = std::chrono::duration<double, std::milli>(end - begin).count();
    frame.last_frame_ms = work;
    if (s.stats) {
      const double interval = std::chrono::duration<double, std::milli>(end - last_present).count();
      s.stats->add(result.frames == 0 ? work : interval, work);
    }
    last_present = end;
    ++result.frames;
    if (kiosk) {
      if (frame.width != shown_w || frame.height != shown_h) {  // first, or a new mode
        shown_w = frame.width;
        shown_h = frame.height;
        kiosk->set_output(Kiosk::Output::kDrawing, shown_w, shown_h);
      }
      ++fps_frames;
      const double window = std::chrono::duration<double>(end - fps_since).count();
      if (window >= 1.0) {
        kiosk->set_fps(static_cast<float>(static_cast<double>(fps_frames) / window));
        fps_frames = 0;
        fps_since = end;
      }
    }
    // Only here, after a present: a loop stuck anywhere stops the watchdog pings.
    if (s.notify) s.notify->frame_presented(result.frames, end);
    if (self_paced) std::this_thread::sleep_until(begin + frame_period);
  }
  result.steps = clock.steps();
  return result;
}
}  // namespace

LoopResult run_frame_loop(Display& display, Scene& scene, const LoopSettings& s) {
  return run_loop(display, &scene, nullptr, s);
}

LoopResult run_frame_loop(Display& display, std::unique_ptr<Scene>& scene, const LoopSettings& s) {
  return run_loop(display, scene.get(), &scene, s);
}

}  // namespace candela
