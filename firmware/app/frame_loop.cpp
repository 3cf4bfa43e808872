#include "app/frame_loop.h"

#include <algorithm>
#include <chrono>
#include <thread>

#include "app/sd_notify.h"
#include "core/clock.h"
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
}  // namespace

LoopResult run_frame_loop(Display& display, Scene& scene, const LoopSettings& s) {
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

  auto do_step = [&] {
    step.step = clock.steps();
    step.time = clock.seconds();
    scene.update(step);
    if (s.sound) {
      SoundCue cue = scene.sound_cue();
      if (s.inputs) cue.volume = s.inputs->volume();  // the `volume` commands' (an atomic)
      s.sound->push(cue);
    }
    clock.tick();
  };
  // Frame 0 shows the state after the first step.
  do_step();
  auto last_present = Clock::now();
  auto prev_begin = last_present;
  while (s.max_frames == 0 || result.frames < s.max_frames) {
    if (s.stop && s.stop->load(std::memory_order_relaxed)) break;
    if (!display.poll_events(keys)) {
      result.quit_requested = true;
      break;
    }
    if (s.inputs) s.inputs->drain(scene.wind());
    const auto begin = Clock::now();
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
      s.inputs->publish(clock.steps(), result.frames, scene.wind().sample(Vec3{}),
                        scene.candles_lit());
    scene.draw(frame);
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
    // Only here, after a present: a loop stuck anywhere stops the watchdog pings.
    if (s.notify) s.notify->frame_presented(result.frames, end);
    if (self_paced) std::this_thread::sleep_until(begin + frame_period);
  }
  result.steps = clock.steps();
  return result;
}

}  // namespace candela
