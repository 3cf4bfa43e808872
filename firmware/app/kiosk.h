// The kiosk's live control (issue 16): scene, brightness, screen power,
// reload and the [schedule], without restarting. Commands arrive on the
// control socket's and MQTT's threads (input/kiosk_control.h), SIGHUP and the
// schedule on the kiosk's own thread; the frame loop only reads atomics and,
// when a new scene is waiting, takes it with a try-lock:
//   - a scene (`scene NAME|PATH`, `reload`, a schedule range) is read and
//     validated on the asking thread; a broken one is answered with its
//     error and the running one stays. The frame loop builds the new Scene
//     (GL work needs its context) between two frames and cross-fades from
//     the old one's last frame over about a second: no black frame;
//   - brightness and the schedule's fade/night level: a multiplier the
//     frame loop glides to and applies at the end of each frame;
//   - screen off: the frame loop stops drawing and presenting, switches the
//     display off (Display::set_screen_power) and sleeps until woken.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "app/schedule.h"
#include "core/clock.h"
#include "display/cec_switch.h"
#include "input/kiosk_control.h"
#include "scene/scene_file.h"

namespace candela {

class SdNotify;

struct KioskOptions {
  std::string config;     // --config: re-read by `reload` and SIGHUP; empty: none
  std::string cli_scene;  // --scene on the command line (wins over the config's)
  bool test_pattern = false;
  std::string scene_label;  // what the running scene is called ("default", a path)
  // The config's (or --scene's) scene, shown outside the schedule's scene
  // ranges; empty: scene_label.
  std::string config_scene;
  int steps_per_second = 60;  // the running loop's: a scene with another rate is refused
  uint64_t seed = 0;          // --seed (0: each scene's own): scenes are prepared for it
  Schedule schedule;
  float brightness = 1.0f;
  int64_t scene_timeout_ms = 60'000;  // how long a command waits for the frame loop to build it
};

class Kiosk final : public KioskControl {
 public:
  Kiosk(KioskOptions options, const WallClock& clock, SdNotify* notify = nullptr);
  ~Kiosk() override;
  Kiosk(const Kiosk&) = delete;
  Kiosk& operator=(const Kiosk&) = delete;

  // The kiosk's thread: SIGHUP reloads (request_reload) and the schedule.
  void start();
  void stop();
  // Async-signal-safe: asks the kiosk's thread to reload.
  void request_reload();
  int reload_fd() const { return reload_fd_; }

  // KioskControl (control socket and MQTT threads).
  std::string command(const ControlCommand& c) override;
  KioskStatus status() const override;

  // Re-reads the config and its scene (the schedule's, if one applies now)
  // and hands it to the frame loop. Any thread but the frame loop's. "ok"
  // or "error: ...".
  std::string reload();
  // Loads NAME (a built-in scene) or PATH, validates it and waits for the
  // frame loop to show it. "ok" or "error: ...".
  std::string show_scene(const std::string& name_or_path);
  // One schedule step at the clock's time (the kiosk's thread calls it
  // every 100 ms; tests may call it themselves).
  void apply_schedule();
  std::string schedule_text() const;

  // --- The frame loop's side: atomics and a try-lock only. ---
  bool screen_on() const { return screen_on_.load(std::memory_order_acquire); }
  // What the frame loop glides to: brightness x the schedule's level.
  float target_level() const {
    return brightness_.load(std::memory_order_relaxed) *
           schedule_level_.load(std::memory_order_relaxed);
  }
  // The schedule's share of the volume (fades, night_volume): the sound's
  // level is the `volume` command's times this.
  float volume_level() const { return schedule_volume_.load(std::memory_order_relaxed); }
  bool scene_waiting() const { return scene_waiting_.load(std::memory_order_acquire); }
  // The waiting scene, or null (none, or the lock is busy: try next frame).
  std::unique_ptr<SceneDesc> take_scene();
  // After building what take_scene() gave: empty, or why it failed.
  void scene_built(const std::string& error);
  void set_fps(float fps) { fps_.store(fps, std::memory_order_relaxed); }
  // Where the frames go (status().display): the loop reports each change.
  enum class Output : int { kStarting, kDrawing, kWaiting };
  void set_output(Output o, int width, int height) {
    output_size_.store(static_cast<int64_t>(width) << 32 | static_cast<uint32_t>(height),
                       std::memory_order_relaxed);
    output_.store(static_cast<int>(o), std::memory_order_release);
  }
  // Screen off: sleeps until a command wakes the loop or `ms` pass.
  void wait_for_wake(int ms) const;

  // Also the screen commands' path (the schedule uses it).
  void set_screen(bool on, const char* why);

  // A switch for the TV itself beside the display's DPMS (HDMI-CEC:
  // open_cec_switch), opened and driven on a thread of its own (a CEC call
  // can take seconds): it follows every screen change, starting with the
  // state now. `open` returning null: DPMS only.
  void start_power_switch(std::function<std::unique_ptr<ScreenPowerSwitch>()> open);
  // Screen changes the switch has carried out (tests).
  uint64_t power_switched() const { return power_switched_.load(std::memory_order_acquire); }

 private:
  void thread_main();
  void wake_loop() const;
  std::string load_and_show(const std::string& name_or_path, bool from_reload);

  KioskOptions o_;
  const WallClock& clock_;
  SdNotify* notify_;
  std::atomic<bool> screen_on_{true};
  std::atomic<float> brightness_{1.0f}, schedule_level_{1.0f}, schedule_volume_{1.0f}, fps_{0.0f};
  std::atomic<int> output_{0};           // Output
  std::atomic<int64_t> output_size_{0};  // width << 32 | height
  mutable std::mutex mu_;                // label_, schedule, the scene hand-over
  std::condition_variable built_cv_;
  std::string label_;
  std::string config_scene_;  // the config's (or command line's) scene: outside schedule ranges
  int schedule_scene_ = -2;   // the schedule's scene range last applied (-2: none yet)
  int schedule_on_ = -1;      // the schedule's on/off last applied (-1: none yet)
  std::unique_ptr<SceneDesc> pending_;
  std::string pending_label_;
  std::atomic<bool> scene_waiting_{false};
  uint64_t handed_ = 0, built_ = 0;  // hand-overs made and answered
  std::string built_error_;
  std::mutex load_mu_;  // one scene load at a time
  int reload_fd_ = -1;  // eventfd: SIGHUP -> the kiosk's thread
  int wake_fd_ = -1;    // eventfd: commands -> a frame loop asleep with the screen off
  std::atomic<bool> stop_{false};
  std::thread thread_;
  std::mutex power_mu_;
  std::condition_variable power_cv_;
  uint64_t power_requests_ = 0;  // under power_mu_
  std::atomic<uint64_t> power_switched_{0};
  std::thread power_thread_;
};

// The scene a kiosk starts with: --test-pattern, --scene, the config's, or
// the built-in default, as a label ("default", "test-pattern", a path).
SceneDesc load_scene_by_label(const std::string& label);
// A label is a scene's name (a built-in one) unless it has a '/' or ends in
// ".toml" (a file's path).
bool is_scene_name(const std::string& label);
// The built-in scenes a person would pick (not the benchmarks'): names for
// `scene NAME` and MQTT's scene select.
std::vector<std::string> builtin_scene_names();
// The same, as a list for messages: "default, eigen-candle, ...".
std::string builtin_scene_list();

}  // namespace candela
