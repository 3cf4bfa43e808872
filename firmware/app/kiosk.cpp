#include "app/kiosk.h"

#include <poll.h>
#include <sys/eventfd.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>

#include "app/config_file.h"
#include "app/sd_notify.h"
#include "core/error.h"
#include "core/log.h"
#include "embedded_scenes.h"
#include "params/params.h"
#include "scene/scene.h"

namespace candela {
std::string builtin_scene_list() {
  std::string out;
  for (const auto& n : builtin_scene_names()) out += (out.empty() ? "" : ", ") + n;
  return out;
}

bool is_scene_name(const std::string& label) {
  return label.find('/') == std::string::npos && !label.ends_with(".toml");
}

std::vector<std::string> builtin_scene_names() {
  std::vector<std::string> out;
  for (size_t i = 0; i < scenes::count(); ++i) {
    std::string_view n = scenes::name_at(i);
    if (n.ends_with(".toml")) n.remove_suffix(5);
    if (n.starts_with("bench-") || n.starts_with("eigen-bench-")) continue;
    out.emplace_back(n);
  }
  return out;
}

SceneDesc load_scene_by_label(const std::string& label) {
  if (!is_scene_name(label)) return load_scene_file(label);
  if (scenes::find(label + ".toml").empty())
    throw ConfigError("scene \"" + echo_value(label) + "\"", "",
                      "no such built-in scene (built in: " + builtin_scene_list() +
                          "; a file needs a path, e.g. ./my.toml)");
  return load_builtin_scene(label);
}

Kiosk::Kiosk(KioskOptions options, const WallClock& clock, SdNotify* notify)
    : o_(std::move(options)), clock_(clock), notify_(notify) {
  label_ = o_.scene_label;
  config_scene_ = o_.config_scene.empty() ? o_.scene_label : o_.config_scene;
  brightness_.store(o_.brightness, std::memory_order_relaxed);
  reload_fd_ = eventfd(0, EFD_CLOEXEC | EFD_NONBLOCK);
  wake_fd_ = eventfd(0, EFD_CLOEXEC | EFD_NONBLOCK);
  if (reload_fd_ < 0 || wake_fd_ < 0)
    LOG_ERROR("kiosk: eventfd: %s; SIGHUP and waking a sleeping screen are off",
              std::strerror(errno));
  if (o_.schedule.present) {
    // What the schedule says now is what main() started with.
    const ScheduleNow n = evaluate_schedule(o_.schedule, local_time(clock_.now_ms() / 1000));
    schedule_scene_ = n.scene;  // main() started with the schedule's scene for now
  }
}

Kiosk::~Kiosk() {
  stop();
  if (reload_fd_ >= 0) close(reload_fd_);
  if (wake_fd_ >= 0) close(wake_fd_);
}

void Kiosk::start() {
  if (thread_.joinable()) return;
  stop_.store(false);
  thread_ = std::thread([this] { thread_main(); });
}

void Kiosk::stop() {
  stop_.store(true);
  request_reload();  // wakes the thread
  // Taking each lock once orders stop_ before the waiters' next check.
  { std::lock_guard lock(mu_); }
  built_cv_.notify_all();
  { std::lock_guard lock(power_mu_); }
  power_cv_.notify_all();
  if (thread_.joinable()) thread_.join();
  if (power_thread_.joinable()) power_thread_.join();
}

void Kiosk::start_power_switch(std::function<std::unique_ptr<ScreenPowerSwitch>()> open) {
  if (power_thread_.joinable()) return;
  power_thread_ = std::thread([this, open = std::move(open)] {
    std::unique_ptr<ScreenPowerSwitch> sw = open();
    if (!sw) return;
    int applied = -1;
    uint64_t seen = 0;
    while (!stop_.load()) {
      const bool want = screen_on();
      if (static_cast<int>(want) != applied) {
        sw->set_power(want);
        applied = want ? 1 : 0;
        power_switched_.fetch_add(1, std::memory_order_release);
      }
      std::unique_lock lock(power_mu_);
      power_cv_.wait(lock, [&] { return power_requests_ != seen || stop_.load(); });
      seen = power_requests_;
    }
  });
}

void Kiosk::request_reload() {
  if (reload_fd_ < 0) return;
  const uint64_t one = 1;
  (void)!write(reload_fd_, &one, sizeof one);
}

void Kiosk::wake_loop() const {
  if (wake_fd_ < 0) return;
  const uint64_t one = 1;
  (void)!write(wake_fd_, &one, sizeof one);
}

void Kiosk::wait_for_wake(int ms) const {
  if (wake_fd_ < 0) {
    poll(nullptr, 0, ms);
    return;
  }
  pollfd p{wake_fd_, POLLIN, 0};
  if (poll(&p, 1, ms) > 0) {
    uint64_t v = 0;
    (void)!read(wake_fd_, &v, sizeof v);
  }
}

void Kiosk::thread_main() {
  while (!stop_.load()) {
    pollfd p{reload_fd_, POLLIN, 0};
    const int n = poll(&p, reload_fd_ >= 0 ? 1 : 0, 100);
    if (stop_.load()) break;
    if (n > 0) {
      uint64_t v = 0;
      (void)!read(reload_fd_, &v, sizeof v);
      LOG_INFO("SIGHUP: reloading");
      const std::string r = reload();
      if (r != "ok") LOG_ERROR("reload: %s", r.c_str());
    }
    apply_schedule();  // nothing without a [schedule] (checked under the lock: reload replaces it)
  }
}

void Kiosk::set_screen(bool on, const char* why) {
  if (screen_on_.exchange(on, std::memory_order_acq_rel) != on)
    LOG_INFO("screen %s (%s)", on ? "on" : "off", why);
  wake_loop();
  {
    std::lock_guard lock(power_mu_);
    ++power_requests_;
  }
  power_cv_.notify_all();
}

KioskStatus Kiosk::status() const {
  KioskStatus s;
  {
    std::lock_guard lock(mu_);
    s.scene = label_;
  }
  s.brightness = brightness_.load(std::memory_order_relaxed);
  s.screen_on = screen_on();
  s.fps = fps_.load(std::memory_order_relaxed);
  const auto output = static_cast<Output>(output_.load(std::memory_order_acquire));
  const int64_t size = output_size_.load(std::memory_order_relaxed);
  s.width = static_cast<int>(size >> 32);
  s.height = static_cast<int>(static_cast<uint32_t>(size));
  s.display = !s.screen_on                 ? "off"
              : output == Output::kDrawing ? "drawing"
              : output == Output::kWaiting ? "waiting"
                                           : "starting";
  return s;
}

std::string Kiosk::command(const ControlCommand& c) {
  char buf[32];
  switch (c.kind) {
    case ControlCommand::Kind::kScene:
      return show_scene(c.scene);
    case ControlCommand::Kind::kBrightness:
      if (c.volume < 0) {
        std::snprintf(buf, sizeof buf, "%.3f",
                      static_cast<double>(brightness_.load(std::memory_order_relaxed)));
        return buf;
      }
      brightness_.store(c.volume, std::memory_order_relaxed);
      return "ok";
    case ControlCommand::Kind::kScreen:
      if (c.screen < 0) return screen_on() ? "on" : "off";
      set_screen(c.screen == 1, "command");
      return "ok";
    case ControlCommand::Kind::kReload:
      return reload();
    case ControlCommand::Kind::kSchedule:
      return schedule_text();
    default:
      return "error: not a kiosk command";
  }
}

std::string Kiosk::show_scene(const std::string& name_or_path) {
  return load_and_show(name_or_path, false);
}

std::string Kiosk::load_and_show(const std::string& label, bool from_reload) {
  std::lock_guard one(load_mu_);
  auto desc = std::make_unique<SceneDesc>();
  try {
    *desc = load_scene_by_label(label);
  } catch (const std::exception& e) {
    return std::string("error: ") + e.what() + "; the running scene stays";
  }
  const std::vector<std::string> problems = scene_problems(*desc);
  if (!problems.empty()) return "error: " + problems.front() + "; the running scene stays";
  if (desc->steps_per_second != o_.steps_per_second)
    return "error: " + desc->file + ": steps_per_second " + std::to_string(desc->steps_per_second) +
           " differs from the running " + std::to_string(o_.steps_per_second) +
           " (a restart changes it); the running scene stays";
  // The elements' GL-free work (a story's plan for its element's seed) here,
  // not in the frame loop that builds the scene.
  prepare_scene(*desc, o_.seed);
  std::unique_lock lock(mu_);
  pending_ = std::move(desc);
  pending_label_ = label;
  const uint64_t id = ++handed_;
  scene_waiting_.store(true, std::memory_order_release);
  wake_loop();
  const bool answered = built_cv_.wait_for(lock, std::chrono::milliseconds(o_.scene_timeout_ms),
                                           [&] { return built_ >= id || stop_.load(); });
  if (!answered || built_ < id) {
    if (pending_) {  // never taken: withdrawn
      pending_.reset();
      scene_waiting_.store(false, std::memory_order_release);
    }
    return "error: the display did not take the scene within " +
           std::to_string(o_.scene_timeout_ms / 1000) + " s";
  }
  if (!built_error_.empty()) return "error: " + built_error_ + "; the running scene stays";
  LOG_INFO("scene: now %s%s", label.c_str(), from_reload ? " (reloaded)" : "");
  return "ok";
}

std::unique_ptr<SceneDesc> Kiosk::take_scene() {
  std::unique_lock lock(mu_, std::try_to_lock);
  if (!lock.owns_lock()) return nullptr;
  scene_waiting_.store(false, std::memory_order_release);
  return std::move(pending_);
}

void Kiosk::scene_built(const std::string& error) {
  {
    std::lock_guard lock(mu_);
    built_ = handed_;
    built_error_ = error;
    if (error.empty()) label_ = pending_label_;
  }
  built_cv_.notify_all();
}

std::string Kiosk::reload() {
  if (notify_) notify_->reloading();
  std::string scene = o_.test_pattern ? "test-pattern" : o_.cli_scene;
  std::string result;
  if (!o_.config.empty()) {
    try {
      KioskConfig c = load_config_file(o_.config);
      if (scene.empty()) scene = c.scene;
      std::lock_guard lock(mu_);
      o_.schedule = std::move(c.schedule);
      schedule_on_ = -1;  // applied afresh
    } catch (const std::exception& e) {
      result = std::string("error: ") + e.what() + "; the running settings stay";
    }
  }
  if (result.empty()) {
    if (scene.empty()) scene = "default";
    std::string show = scene;
    {
      std::lock_guard lock(mu_);
      config_scene_ = scene;
      if (o_.schedule.present) {
        const ScheduleNow n = evaluate_schedule(o_.schedule, local_time(clock_.now_ms() / 1000));
        schedule_scene_ = n.scene;
        show = scheduled_scene(o_.schedule, n, scene);
      } else {
        schedule_level_.store(1.0f, std::memory_order_relaxed);
        schedule_volume_.store(1.0f, std::memory_order_relaxed);
      }
    }
    result = load_and_show(show, true);
    apply_schedule();
  }
  if (notify_) notify_->reloaded();
  return result;
}

void Kiosk::apply_schedule() {
  std::string show;
  {
    std::lock_guard lock(mu_);
    const Schedule& s = o_.schedule;
    if (!s.present) return;
    const ScheduleNow n = evaluate_schedule(s, local_time(clock_.now_ms() / 1000));
    schedule_level_.store(static_cast<float>(n.level), std::memory_order_relaxed);
    schedule_volume_.store(static_cast<float>(n.volume), std::memory_order_relaxed);
    if (s.has_days && static_cast<int>(n.on) != schedule_on_) {
      const bool first = schedule_on_ < 0;
      schedule_on_ = n.on ? 1 : 0;
      // The schedule's changes win; between them, `screen` commands do.
      if (!first || screen_on() != n.on) set_screen(n.on, "schedule");
    }
    if (!s.scenes.empty() && n.scene != schedule_scene_) {
      schedule_scene_ = n.scene;
      show = scheduled_scene(s, n, config_scene_);
    }
  }
  if (!show.empty()) {
    const std::string r = load_and_show(show, false);
    if (r != "ok") LOG_ERROR("schedule: scene %s: %s", show.c_str(), r.c_str());
  }
}

std::string Kiosk::schedule_text() const {
  std::lock_guard lock(mu_);
  return describe_schedule(o_.schedule, local_time(clock_.now_ms() / 1000), config_scene_);
}

}  // namespace candela
