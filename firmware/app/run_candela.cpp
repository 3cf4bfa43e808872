#include "app/run_candela.h"

#include <cstdio>
#include <memory>
#include <string>

#include "app/frame_loop.h"
#include "app/kiosk.h"
#include "app/sd_notify.h"
#include "app/signals.h"
#include "core/log.h"
#include "display/cec_switch.h"
#include "display/display.h"
#include "input/input_hub.h"
#include "input/mqtt_bridge.h"
#include "scene/scene.h"
#include "sound/sound_output.h"

namespace candela {
namespace {

// The scene's [sound], unless --mute.
bool sound_on(const Options& opt, const SceneDesc& desc) { return desc.sound.enabled && !opt.mute; }

// Headless writing frames: the sound goes beside them (muxed into a video);
// a screen, or headless --realtime without --out (a board heard, not seen):
// ALSA. Headless otherwise: no sound.
std::unique_ptr<SoundOutput> open_sound(const Options& opt, const SceneDesc& desc,
                                        const Display& display) {
  if (!sound_on(opt, desc)) return nullptr;
  const uint64_t seed =
      desc.sound.seed ? desc.sound.seed : (opt.seed ? opt.seed : desc.seed) ^ 0x736f756e64ULL;
  if (display.name() != "headless" || (opt.realtime && opt.display.out_path.empty()))
    return open_sound_device(desc.sound, desc.steps_per_second, seed);
  if (opt.display.out_path.empty()) return nullptr;
  LOG_INFO("sound: writing %s", opt.display.sound_path.c_str());
  return open_sound_recording(desc.sound, desc.steps_per_second, seed, opt.display.sound_path);
}

// The scene, or the built-in default where every element failed to create
// (logged above): not a black screen.
std::unique_ptr<Scene> build_scene(StartScene& start, uint64_t seed) {
  SceneDesc& desc = start.desc;
  prepare_scene(desc, seed);  // what the elements do without GL (a story's plan)
  auto scene = std::make_unique<Scene>(desc, seed, &stop_requested());
  if (!stop_requested() && !desc.elements.empty() && scene->element_count() == 0 &&
      desc.file != "<built-in default>") {
    LOG_ERROR("%s: no element could be created; showing the built-in default scene instead",
              desc.file.c_str());
    desc = load_builtin_scene("default");
    scene = std::make_unique<Scene>(desc, seed, &stop_requested());
  }
  if (desc.file == "<built-in default>" && start.label != "default") start.label = "default";
  return scene;
}

KioskOptions kiosk_options(const Options& opt, const StartScene& start) {
  KioskOptions ko;
  ko.config = opt.config;
  ko.cli_scene = opt.scene_from_cli ? start.config_label : std::string();
  ko.test_pattern = opt.test_pattern;
  ko.scene_label = start.label;
  ko.config_scene = start.config_label;
  ko.steps_per_second = start.desc.steps_per_second;
  ko.seed = opt.seed;
  ko.schedule = opt.schedule;
  return ko;
}

// A thread only where there is something to watch: SIGHUP with a config to
// re-read, or a schedule; the TV itself too (HDMI-CEC) where candela owns the screen.
void start_kiosk(Kiosk& kiosk, const Options& opt, const Display& display) {
  if (!opt.config.empty() || opt.schedule.present) kiosk.start();
  if (!opt.config.empty()) reload_on_sighup(&kiosk);
  if (opt.schedule.present) kiosk.apply_schedule();  // off now: off from the first frame
  if (display.name() == "drm") kiosk.start_power_switch(open_cec_switch);
}

// Several screens, one room: only with [room] (and [mqtt]).
void start_inputs(InputHub& inputs, Options& opt, const SceneDesc& desc, Kiosk& kiosk) {
  inputs.set_volume(desc.sound.volume);
  inputs.set_kiosk(&kiosk);
  if (opt.mqtt.enabled && opt.mqtt.room.enabled)
    inputs.enable_room(opt.mqtt.room.x, opt.mqtt.room.z);
  else
    opt.mqtt.room.enabled = false;
  inputs.start();
}

void log_run(const LoopResult& r) {
  const auto n = [](uint64_t v) { return static_cast<unsigned long long>(v); };
  if (r.frames_asleep)
    LOG_INFO("%llu frames, %llu steps; %llu frame periods with nothing shown (screen off)",
             n(r.frames), n(r.steps), n(r.frames_asleep));
  else
    LOG_INFO("%llu frames, %llu steps", n(r.frames), n(r.steps));
}

}  // namespace

int run_candela(Options& opt, StartScene start, const WallClock& wall) {
  const SceneDesc& desc = start.desc;
  if (opt.display.width == 0 && desc.width > 0) {
    opt.display.width = desc.width;
    opt.display.height = desc.height;
  }
  if (opt.display.refresh_hz == 0) opt.display.refresh_hz = desc.refresh_hz;
  // Before any thread starts (it unsets the variables it reads).
  SdNotify notify = SdNotify::from_environment(desc.file);
  if (sound_on(opt, desc) && !opt.display.out_path.empty())
    opt.display.sound_path = sound_path_for(opt.display.out_path);
  try {
    auto display = open_display(opt.display);
    std::unique_ptr<SoundOutput> sound = open_sound(opt, desc, *display);
    std::unique_ptr<Scene> scene = build_scene(start, opt.seed);
    if (stop_requested()) {
      LOG_INFO("stopped by %s while the scene was built", stop_signal_name());
      if (sound) sound->finish();
      display->finish();
      return 0;
    }
    FrameStats stats(opt.frames ? opt.frames : (1u << 16));  // at most FrameStats::kMaxFrames
    Kiosk kiosk(kiosk_options(opt, start), wall, &notify);
    start_kiosk(kiosk, opt, *display);
    InputHub inputs(desc.inputs, desc.wind, opt.control);
    start_inputs(inputs, opt, desc, kiosk);
    // Off unless the config has [mqtt]: nothing connects or listens then.
    std::unique_ptr<MqttBridge> mqtt;
    if (opt.mqtt.enabled) {
      opt.mqtt.scenes = builtin_scene_names();
      mqtt = std::make_unique<MqttBridge>(opt.mqtt, inputs);
      mqtt->start();
    }
    LoopSettings ls;
    ls.max_frames = opt.frames;
    ls.steps_per_second = desc.steps_per_second;
    ls.frames_per_second = opt.display.fps;
    ls.stop = &stop_requested();
    ls.realtime = opt.realtime;
    ls.stats = &stats;
    ls.inputs = &inputs;
    ls.notify = &notify;
    ls.sound = sound.get();
    ls.kiosk = &kiosk;
    ls.seed = opt.seed;
    const double cpu0 = process_cpu_seconds();
    const LoopResult r = run_frame_loop(*display, scene, ls);
    notify.stopping();
    reload_on_sighup(nullptr);
    kiosk.stop();
    const double cpu = process_cpu_seconds() - cpu0;
    if (mqtt) mqtt->stop();      // "offline" on the availability topic
    if (sound) sound->finish();  // the .wav complete before the video muxes it
    display->finish();
    if (stop_requested()) LOG_INFO("stopped by %s; outputs finished", stop_signal_name());
    log_run(r);
    if (opt.bench)
      std::printf("%s\n",
                  stats
                      .json(r.frames, cpu, display->missed_vblanks(), std::string(display->name()),
                            display->width(), display->height(), start.desc.file)
                      .c_str());
  } catch (const std::exception& e) {
    LOG_ERROR("%s", e.what());
    return 1;
  }
  return 0;
}

}  // namespace candela
