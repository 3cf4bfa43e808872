// candela: the runtime. A thin main over the candela_runtime library.
#include <signal.h>

#include <atomic>
#include <csignal>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "app/frame_loop.h"
#include "app/kiosk.h"
#include "app/options.h"
#include "app/sd_notify.h"
#include "core/error.h"
#include "core/log.h"
#include "display/cec_switch.h"
#include "display/display.h"
#include "input/input_hub.h"
#include "input/mqtt_bridge.h"
#include "scene/scene.h"
#include "scene/scene_file.h"
#include "sound/sound_output.h"

namespace {
std::atomic<bool> g_stop{false};
volatile std::sig_atomic_t g_signal = 0;
candela::Kiosk* volatile g_kiosk = nullptr;  // set while SIGHUP means "reload"
void on_signal(int sig) {
  g_signal = sig;
  g_stop = true;
}
// With --config, SIGHUP re-reads it (the kiosk's reload; async-signal-safe:
// an eventfd write).
void on_reload_signal(int) {
  if (candela::Kiosk* k = g_kiosk) k->request_reload();
}

// SIGTERM (systemd), SIGINT (Ctrl-C) and SIGHUP (a closed terminal) end the
// run cleanly: the frame loop stops, every output is finished (an mp4 gets
// its index, no PNG .tmp or partial y4m frame is left) and candela exits 0.
// A second one of them kills at once (SA_RESETHAND), for a stuck shutdown.
// SIGPIPE is ignored: a write to a gone reader (ffmpeg, a control client)
// returns EPIPE and is reported, instead of killing the display silently.
// With --config (a kiosk), SIGHUP reloads instead (install_reload_handler).
void install_signal_handlers() {
  struct sigaction sa {};
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESETHAND;
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) sigaction(sig, &sa, nullptr);
  std::signal(SIGPIPE, SIG_IGN);
}
void install_reload_handler() {
  struct sigaction sa {};
  sa.sa_handler = on_reload_signal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESTART;
  sigaction(SIGHUP, &sa, nullptr);
}

const char* signal_name(int sig) {
  return sig == SIGTERM  ? "SIGTERM"
         : sig == SIGINT ? "SIGINT"
         : sig == SIGHUP ? "SIGHUP"
                         : "a signal";
}
}  // namespace

int main(int argc, char** argv) {
  using namespace candela;
  Options opt;
  if (int rc = parse_options(argc, argv, opt); rc >= 0) return rc;
  static const char* const kLevels[] = {"debug", "info", "warn", "error"};
  for (int i = 0; i < 4; ++i)
    if (opt.log_level == kLevels[i]) set_log_level(static_cast<LogLevel>(i));

  if (opt.list_elements) {
    for (const auto& k : element_kinds())
      std::printf("%-14.*s %.*s\n", static_cast<int>(k.name.size()), k.name.data(),
                  static_cast<int>(k.summary.size()), k.summary.data());
    return 0;
  }

  install_signal_handlers();
  // The kiosk's clock (the [schedule]'s): the system's, or a test's.
  SystemWallClock system_clock;
  std::unique_ptr<ScaledWallClock> test_clock;
  if (opt.clock_start_ms >= 0)
    test_clock = std::make_unique<ScaledWallClock>(opt.clock_start_ms, opt.clock_scale);
  const WallClock& wall = test_clock ? static_cast<const WallClock&>(*test_clock) : system_clock;
  // What the kiosk calls the scene (`state`, `reload`): a built-in's name or a path.
  std::string label = opt.test_pattern           ? "test-pattern"
                      : opt.scene.empty()        ? "default"
                      : opt.scene_is_name        ? opt.scene
                      : is_scene_name(opt.scene) ? "./" + opt.scene  // --scene FILE
                                                 : opt.scene;
  const std::string config_label = label;
  if (opt.schedule.present && !opt.test_pattern && !opt.check) {
    const ScheduleNow now = evaluate_schedule(opt.schedule, local_time(wall.now_ms() / 1000));
    if (now.scene >= 0) label = opt.schedule.scenes[static_cast<size_t>(now.scene)].scene;
  }
  SceneDesc desc;
  try {
    desc = opt.test_pattern                          ? load_builtin_scene("test-pattern")
           : opt.scene.empty() && label == "default" ? load_builtin_scene("default")
           : label == config_label && !opt.scene.empty() && !opt.scene_is_name
               ? load_scene_file(opt.scene)
               : load_scene_by_label(label);
  } catch (const ConfigError& e) {
    std::fprintf(stderr, "candela: %s\n", e.what());
    return 2;
  }
  const std::vector<std::string> problems = scene_problems(desc);
  if (opt.check) {
    // What the runtime would work around (a model it replaces with the
    // built-in one, an empty scene) is still an error in the scene file.
    for (const auto& p : problems) std::fprintf(stderr, "candela: error: %s\n", p.c_str());
    // The [schedule]'s scenes too: a kiosk would find a broken one in the evening.
    bool schedule_ok = true;
    for (const auto& range : opt.schedule.scenes) {
      try {
        for (const auto& p : scene_problems(load_scene_by_label(range.scene))) {
          std::fprintf(stderr, "candela: error: %s: schedule.scenes.\"%s\": %s\n",
                       opt.config.c_str(), range.range.c_str(), p.c_str());
          schedule_ok = false;
        }
      } catch (const ConfigError& e) {
        std::fprintf(stderr, "candela: error: %s: schedule.scenes.\"%s\": %s\n", opt.config.c_str(),
                     range.range.c_str(), e.what());
        schedule_ok = false;
      }
    }
    if (!problems.empty() || !schedule_ok) return 2;
    std::printf("%s: OK (%zu elements)\n", desc.file.c_str(), desc.elements.size());
    return 0;
  }
  // Run anyway (an input-only scene is how sensors are tried out), but say so.
  if (desc.elements.empty()) LOG_WARN("%s", problems.front().c_str());
  if (opt.display.width == 0 && desc.width > 0) {
    opt.display.width = desc.width;
    opt.display.height = desc.height;
  }
  if (opt.display.refresh_hz == 0) opt.display.refresh_hz = desc.refresh_hz;

  // Before any thread starts (it unsets the variables it reads).
  SdNotify notify = SdNotify::from_environment(desc.file);
  const bool sound_on = desc.sound.enabled && !opt.mute;
  if (sound_on && !opt.display.out_path.empty())
    opt.display.sound_path = sound_path_for(opt.display.out_path);
  try {
    auto display = open_display(opt.display);
    // Headless writing frames: the sound goes beside them (muxed into a
    // video); a screen, or headless --realtime without --out (a board heard,
    // not seen): ALSA. Headless otherwise: no sound.
    std::unique_ptr<SoundOutput> sound;
    if (sound_on) {
      const uint64_t seed =
          desc.sound.seed ? desc.sound.seed : (opt.seed ? opt.seed : desc.seed) ^ 0x736f756e64ULL;
      if (display->name() != "headless" || (opt.realtime && opt.display.out_path.empty())) {
        sound = open_sound_device(desc.sound, desc.steps_per_second, seed);
      } else if (!opt.display.out_path.empty()) {
        sound =
            open_sound_recording(desc.sound, desc.steps_per_second, seed, opt.display.sound_path);
        LOG_INFO("sound: writing %s", opt.display.sound_path.c_str());
      }
    }
    prepare_scene(desc, opt.seed);  // what the elements do without GL (a story's plan)
    auto scene_ptr = std::make_unique<Scene>(desc, opt.seed, &g_stop);
    if (!g_stop && !desc.elements.empty() && scene_ptr->element_count() == 0 &&
        desc.file != "<built-in default>") {
      // Every element failed to create (logged above): the default scene, not a black screen.
      LOG_ERROR("%s: no element could be created; showing the built-in default scene instead",
                desc.file.c_str());
      desc = load_builtin_scene("default");
      scene_ptr = std::make_unique<Scene>(desc, opt.seed, &g_stop);
    }
    if (desc.file == "<built-in default>" && label != "default") label = "default";
    if (g_stop) {
      LOG_INFO("stopped by %s while the scene was built", signal_name(g_signal));
      if (sound) sound->finish();
      display->finish();
      return 0;
    }
    FrameStats stats(opt.frames ? opt.frames : (1u << 16));  // at most FrameStats::kMaxFrames
    LoopSettings ls;
    ls.max_frames = opt.frames;
    ls.steps_per_second = desc.steps_per_second;
    ls.frames_per_second = opt.display.fps;
    ls.stop = &g_stop;
    ls.realtime = opt.realtime;
    ls.stats = &stats;
    KioskOptions ko;
    ko.config = opt.config;
    ko.cli_scene = opt.scene_from_cli ? config_label : std::string();
    ko.test_pattern = opt.test_pattern;
    ko.scene_label = label;
    ko.config_scene = config_label;
    ko.steps_per_second = desc.steps_per_second;
    ko.seed = opt.seed;
    ko.schedule = opt.schedule;
    Kiosk kiosk(std::move(ko), wall, &notify);
    // A thread only where there is something to watch: SIGHUP with a
    // config to re-read, or a schedule.
    if (!opt.config.empty() || opt.schedule.present) kiosk.start();
    if (!opt.config.empty()) {
      g_kiosk = &kiosk;
      install_reload_handler();
    }
    if (opt.schedule.present) kiosk.apply_schedule();  // off now: off from the first frame
    // The TV itself too (HDMI-CEC), where candela owns the screen.
    if (display->name() == "drm") kiosk.start_power_switch(open_cec_switch);
    InputHub inputs(desc.inputs, desc.wind, opt.control);
    inputs.set_volume(desc.sound.volume);
    inputs.set_kiosk(&kiosk);
    // Several screens, one room: only with [room] (and [mqtt]).
    if (opt.mqtt.enabled && opt.mqtt.room.enabled)
      inputs.enable_room(opt.mqtt.room.x, opt.mqtt.room.z);
    else
      opt.mqtt.room.enabled = false;
    inputs.start();
    // Off unless the config has [mqtt]: nothing connects or listens then.
    std::unique_ptr<MqttBridge> mqtt;
    if (opt.mqtt.enabled) {
      opt.mqtt.scenes = builtin_scene_names();
      mqtt = std::make_unique<MqttBridge>(opt.mqtt, inputs);
      mqtt->start();
    }
    ls.inputs = &inputs;
    ls.notify = &notify;
    ls.sound = sound.get();
    ls.kiosk = &kiosk;
    ls.seed = opt.seed;
    const double cpu0 = process_cpu_seconds();
    const LoopResult r = run_frame_loop(*display, scene_ptr, ls);
    notify.stopping();
    g_kiosk = nullptr;
    kiosk.stop();
    const double cpu = process_cpu_seconds() - cpu0;
    if (mqtt) mqtt->stop();      // "offline" on the availability topic
    if (sound) sound->finish();  // the .wav complete before the video muxes it
    display->finish();
    if (g_stop) LOG_INFO("stopped by %s; outputs finished", signal_name(g_signal));
    if (r.frames_asleep)
      LOG_INFO("%llu frames, %llu steps; %llu frame periods with nothing shown (screen off)",
               static_cast<unsigned long long>(r.frames), static_cast<unsigned long long>(r.steps),
               static_cast<unsigned long long>(r.frames_asleep));
    else
      LOG_INFO("%llu frames, %llu steps", static_cast<unsigned long long>(r.frames),
               static_cast<unsigned long long>(r.steps));
    if (opt.bench)
      std::printf("%s\n",
                  stats
                      .json(r.frames, cpu, display->missed_vblanks(), std::string(display->name()),
                            display->width(), display->height(), desc.file)
                      .c_str());
  } catch (const std::exception& e) {
    LOG_ERROR("%s", e.what());
    return 1;
  }
  return 0;
}
