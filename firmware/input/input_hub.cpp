#include "input/input_hub.h"

#include <poll.h>
#include <sys/eventfd.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <nlohmann/json.hpp>
#include <optional>

#include "core/json.h"
#include "core/log.h"
#include "input/camera_source.h"
#include "input/control_channel.h"
#include "input/gpio_source.h"
#include "input/key_input.h"
#include "input/kiosk_control.h"
#include "input/room.h"
#include "input/scene_command_worker.h"

namespace candela {

class InputHub::QueueSink final : public InputEventSink {
 public:
  explicit QueueSink(std::function<bool(const InputEvent&)> push) : push_(std::move(push)) {}
  void emit(const InputEvent& e) override {
    if (!push_(e) && !warned_) {
      LOG_WARN("input: event queue full; dropping events (is the frame loop stalled?)");
      warned_ = true;
    }
  }

 private:
  std::function<bool(const InputEvent&)> push_;
  bool warned_ = false;
};

InputHub::InputHub(std::vector<InputSpec> inputs, const WindSpec& wind, std::string control_path)
    : specs_(std::move(inputs)), wind_spec_(wind), control_path_(std::move(control_path)) {
  applied_by_source_ = std::make_unique<std::atomic<uint64_t>[]>(specs_.size() + 1);
  input_sink_ =
      std::make_unique<QueueSink>([this](const InputEvent& e) { return input_queue_.push(e); });
  camera_sink_ =
      std::make_unique<QueueSink>([this](const InputEvent& e) { return camera_queue_.push(e); });
  key_sink_ =
      std::make_unique<QueueSink>([this](const InputEvent& e) { return key_queue_.push(e); });
  gpio_of_spec_.assign(specs_.size(), -1);
  for (size_t i = 0; i < specs_.size(); ++i) {
    if (specs_[i].is_gpio()) {
      gpio_of_spec_[i] = static_cast<int>(gpio_.size());
      gpio_.push_back(std::make_unique<GpioSource>(specs_[i], static_cast<uint16_t>(i), wind));
    } else if (!camera_) {
      camera_ =
          std::make_unique<CameraSource>(specs_[i], static_cast<uint16_t>(i), wind, *camera_sink_);
    } else {
      LOG_WARN("input \"%s\": only one camera input is used; ignoring this one",
               specs_[i].name.c_str());
    }
  }
}

InputHub::~InputHub() { stop(); }

void InputHub::start() {
  if (!control_path_.empty()) {
    try {
      control_ = std::make_unique<ControlServer>(control_path_);
    } catch (const std::exception& e) {
      LOG_ERROR("%s; running without a control channel", e.what());
    }
  }
  if (camera_) camera_->start();
  if (gpio_.empty() && !control_) return;
  stop_fd_ = eventfd(0, EFD_CLOEXEC | EFD_NONBLOCK);
  if (stop_fd_ < 0) {
    LOG_ERROR("input: eventfd: %s; GPIO inputs and the control channel are off",
              std::strerror(errno));
    control_.reset();
    return;
  }
  thread_ = std::thread([this] { input_thread(); });
}

void InputHub::stop() {
  if (thread_.joinable()) {
    const uint64_t one = 1;
    if (write(stop_fd_, &one, sizeof one) < 0) LOG_ERROR("input: cannot stop the input thread");
    thread_.join();
  }
  if (stop_fd_ >= 0) close(stop_fd_);
  stop_fd_ = -1;
  if (camera_) camera_->stop();
  control_.reset();
}

void InputHub::on_key(Key key) {
  const std::optional<WindEvent> wind = key_wind_event(key, wind_spec_);
  if (!wind) return;
  InputEvent e;
  e.wind = *wind;
  e.cause_ns = monotonic_ns();
  e.source = kKeySource;
  key_sink_->emit(e);
}

void InputHub::drain(WindField& wind) {
  InputEvent e;
  int64_t now = 0;
  auto apply = [&](const InputEvent& ev) {
    wind.push(ev.wind);
    if (!now) now = monotonic_ns();
    const int64_t latency = ev.cause_ns > 0 ? now - ev.cause_ns : -1;
    if (latency >= 0) {
      last_latency_ns_.store(latency, std::memory_order_relaxed);
      if (latency > max_latency_ns_.load(std::memory_order_relaxed))
        max_latency_ns_.store(latency, std::memory_order_relaxed);
    }
    // Started here: the room hears of it (a gust from the room is not
    // passed on again: drain_room() applies those).
    if (room_ && ev.wind.type != WindEvent::Type::kSteady) {
      const int64_t t = realtime_ns();
      if (room_out_.push({ev.wind, t})) room_sent_ns_.store(t, std::memory_order_relaxed);
    }
    if (ev.source < specs_.size())
      applied_by_source_[ev.source].fetch_add(1, std::memory_order_relaxed);
    else if (ev.source == kControlSource)
      applied_control_.fetch_add(1, std::memory_order_relaxed);
    applied_.fetch_add(1, std::memory_order_release);
  };
  while (key_queue_.pop(e)) apply(e);  // first, as when keys went straight to the wind
  while (input_queue_.pop(e)) apply(e);
  while (camera_queue_.pop(e)) apply(e);
  while (mqtt_queue_.pop(e)) apply(e);
  if (room_) drain_room(wind);
}

void InputHub::enable_room(double x, double z) {
  room_ = true;
  room_x_ = x;
  room_z_ = z;
}

bool InputHub::give_room_gust(const RoomIn& in) {
  if (room_in_.push(in)) return true;
  room_overflow_.fetch_add(1, std::memory_order_relaxed);
  return false;
}

void InputHub::drain_room(WindField& wind) {
  RoomIn in;
  while (room_in_.pop(in)) {
    if (room_pending_n_ < kRoomPending)
      room_pending_[static_cast<size_t>(room_pending_n_++)] = in;
    else
      room_overflow_.fetch_add(1, std::memory_order_relaxed);
  }
  const int64_t now = monotonic_ns();
  const int64_t before = room_last_drain_ns_;  // the frame before this one
  // Started on the frame nearest its time: up to half a frame early, so
  // the error is within +-half a frame, not 0..1 frame late.
  const int64_t half_frame =
      before > 0 ? std::clamp<int64_t>((now - before) / 2, 0, 10'000'000) : 0;
  room_last_drain_ns_ = now;
  for (int i = 0; i < room_pending_n_;) {
    const RoomIn& g = room_pending_[static_cast<size_t>(i)];
    if (g.due_mono_ns - half_frame > now) {
      ++i;
      continue;
    }
    wind.push(g.wind);
    room_origin_ns_.store(g.origin_ns, std::memory_order_relaxed);
    room_received_ns_.store(g.received_ns, std::memory_order_relaxed);
    room_due_ns_.store(g.due_ns, std::memory_order_relaxed);
    const int64_t real_now = realtime_ns();
    room_applied_ns_.store(real_now, std::memory_order_relaxed);
    // The frame before, on the same clock: a gust started late with that
    // frame before its time waited for the frame loop, not in the queue.
    room_frame_before_ns_.store(before > 0 ? real_now - (now - before) : 0,
                                std::memory_order_relaxed);
    room_applied_.fetch_add(1, std::memory_order_release);
    applied_.fetch_add(1, std::memory_order_release);
    room_pending_[static_cast<size_t>(i)] = room_pending_[static_cast<size_t>(--room_pending_n_)];
  }
  room_waiting_.store(room_pending_n_, std::memory_order_relaxed);
}

void InputHub::publish(uint64_t step, uint64_t frame, WindSample wind, int candles_lit) {
  candles_lit_.store(candles_lit, std::memory_order_relaxed);
  wind_x_.store(wind.x.raw, std::memory_order_relaxed);
  wind_z_.store(wind.z.raw, std::memory_order_relaxed);
  step_.store(step, std::memory_order_relaxed);
  frame_.store(frame, std::memory_order_release);
}

namespace {
using Json = nlohmann::ordered_json;

// A latency in ms to three places; null when none was measured.
Json ms(int64_t ns) {
  if (ns < 0) return nullptr;
  return json_decimals(static_cast<double>(ns) / 1e6, 3);
}
// What `state` and the MQTT summary begin with: frame, step and the wind at
// the origin (x, z to four places).
Json frame_step_wind(uint64_t frame, uint64_t step, int32_t x_raw, int32_t z_raw) {
  Json j;
  j["frame"] = frame;
  j["step"] = step;
  j["wind"] = {{"x", json_decimals(Fixed::from_raw(x_raw).to_double(), 4)},
               {"z", json_decimals(Fixed::from_raw(z_raw).to_double(), 4)}};
  return j;
}
Json lit_json(int n) { return n >= 0 ? Json(n) : Json(nullptr); }
// The kiosk's part of `state` and of MQTT's state: scene, brightness,
// screen, and the error count (errors logged since start).
void add_kiosk(Json& j, const KioskControl* kiosk) {
  if (kiosk) {
    const KioskStatus k = kiosk->status();
    j["scene"] = k.scene;
    j["brightness"] = json_decimals(k.brightness, 3);
    j["screen"] = k.screen_on ? "on" : "off";
    // Where the frames go: a monitor unplugged shows here, not in "screen"
    // (what was asked for). The size is of the frames drawn last.
    j["display"] = {{"status", k.display},
                    {"width", k.width > 0 ? Json(k.width) : Json(nullptr)},
                    {"height", k.height > 0 ? Json(k.height) : Json(nullptr)}};
  }
  j["errors"] = log_error_count();
}
double kiosk_fps(const KioskControl* kiosk) { return kiosk ? kiosk->status().fps : 0.0; }
}  // namespace

std::string InputHub::state_json() const {
  Json j = frame_step_wind(
      frame_.load(std::memory_order_acquire), step_.load(std::memory_order_relaxed),
      wind_x_.load(std::memory_order_relaxed), wind_z_.load(std::memory_order_relaxed));
  j["fps"] = json_decimals(kiosk_fps(kiosk_), 1);
  add_kiosk(j, kiosk_);
  j["events"] = applied_.load(std::memory_order_acquire);
  j["control_events"] = applied_control_.load(std::memory_order_relaxed);
  j["dropped"] = input_queue_.dropped() + camera_queue_.dropped() + mqtt_queue_.dropped() +
                 key_queue_.dropped();
  j["latency_ms"] = {{"last", ms(last_latency_ns_.load(std::memory_order_relaxed))},
                     {"max", ms(max_latency_ns_.load(std::memory_order_relaxed))}};
  j["candles_lit"] = lit_json(candles_lit_.load(std::memory_order_relaxed));
  j["volume"] = json_decimals(static_cast<double>(volume()), 3);
  Json inputs = Json::array();
  for (size_t i = 0; i < specs_.size(); ++i) {
    const InputSpec& s = specs_[i];
    Json in;
    in["name"] = s.name;
    in["kind"] = input_kind_name(s.kind);
    Json extra = Json::object();
    if (gpio_of_spec_[i] >= 0) {
      const GpioSource& g = *gpio_[static_cast<size_t>(gpio_of_spec_[i])];
      in["status"] = g.status();
      in["device"] = g.line_description();
      extra["activations"] = g.logic().activations();
      extra["speed"] = json_decimals(g.logic().speed(), 4);
    } else if (camera_ && camera_->source() == i) {
      in["status"] = camera_->status();
      in["device"] = camera_->device();
      const CameraSource::Stats c = camera_->stats();
      extra["frames"] = c.frames;
      extra["gusts"] = c.gusts;
      extra["fps"] = json_decimals(c.fps, 2);
      extra["cpu_percent"] = json_decimals(c.cpu_percent, 3);
    } else {
      in["status"] = "ignored";
      in["device"] = "";
    }
    in["events"] = applied_by_source_[i].load(std::memory_order_relaxed);
    in.update(extra);
    inputs.push_back(std::move(in));
  }
  j["inputs"] = std::move(inputs);
  if (room_) {
    // The room (input/room.h): the last received gust's times are
    // CLOCK_REALTIME ns: when it left its origin, when its message came in
    // here, when it was due here (origin + the plane-S delay for this
    // position), when it was started here.
    auto count = [&](RoomNote n) {
      return room_counts_[static_cast<int>(n)].load(std::memory_order_relaxed);
    };
    Json room;
    room["position"] = {room_x_, room_z_};
    room["sent"] = count(RoomNote::kSent);
    room["received"] = count(RoomNote::kReceived);
    room["applied"] = room_applied_.load(std::memory_order_acquire);
    room["waiting"] = room_waiting_.load(std::memory_order_relaxed);
    room["late"] = count(RoomNote::kLate);
    room["own"] = count(RoomNote::kOwn);
    room["upwind"] = count(RoomNote::kUpwind);
    room["invalid"] = count(RoomNote::kInvalid);
    room["dropped"] = room_overflow_.load(std::memory_order_relaxed) + room_out_.dropped();
    room["last_sent_ns"] = room_sent_ns_.load(std::memory_order_relaxed);
    room["last"] = {{"origin_ns", room_origin_ns_.load(std::memory_order_relaxed)},
                    {"received_ns", room_received_ns_.load(std::memory_order_relaxed)},
                    {"due_ns", room_due_ns_.load(std::memory_order_relaxed)},
                    {"applied_ns", room_applied_ns_.load(std::memory_order_relaxed)},
                    {"frame_before_ns", room_frame_before_ns_.load(std::memory_order_relaxed)}};
    j["room"] = std::move(room);
  }
  return j.dump(-1, ' ', false, Json::error_handler_t::replace);
}

std::string InputHub::summary_json() const {
  // fps with frame and step, before "wind": MQTT republishes on a change of
  // what follows "wind" only (mqtt_bridge.cpp), not on every frame.
  Json j;
  j["frame"] = frame_.load(std::memory_order_acquire);
  j["step"] = step_.load(std::memory_order_relaxed);
  j["fps"] = json_decimals(kiosk_fps(kiosk_), 1);
  j["wind"] = {
      {"x", json_decimals(Fixed::from_raw(wind_x_.load(std::memory_order_relaxed)).to_double(), 4)},
      {"z",
       json_decimals(Fixed::from_raw(wind_z_.load(std::memory_order_relaxed)).to_double(), 4)}};
  j["volume"] = json_decimals(static_cast<double>(volume()), 3);
  j["candles_lit"] = lit_json(candles_lit_.load(std::memory_order_relaxed));
  j["events"] = applied_.load(std::memory_order_acquire);
  add_kiosk(j, kiosk_);
  return j.dump(-1, ' ', false, Json::error_handler_t::replace);
}

std::string InputHub::answer(std::string_view line, Origin origin) {
  return answer_command(parse_control_command(line, wind_spec_), origin);
}

std::string InputHub::answer_command(const ControlCommand& c, Origin origin) {
  switch (c.kind) {
    case ControlCommand::Kind::kWind: {
      InputEvent e;
      e.wind = c.event;
      e.cause_ns = monotonic_ns();
      e.source = kControlSource;
      const bool queued = origin == Origin::kMqtt ? mqtt_queue_.push(e) : input_queue_.push(e);
      return queued ? "ok" : "error: event queue full";
    }
    case ControlCommand::Kind::kVolume: {
      char buf[32];
      if (c.volume < 0) {
        std::snprintf(buf, sizeof buf, "%.3f", static_cast<double>(volume()));
        return buf;
      }
      set_volume(c.volume);
      return "ok";
    }
    case ControlCommand::Kind::kState:
      // The inputs' own status is the input thread's to read.
      return origin == Origin::kMqtt ? summary_json() : state_json();
    case ControlCommand::Kind::kScene:
    case ControlCommand::Kind::kBrightness:
    case ControlCommand::Kind::kScreen:
    case ControlCommand::Kind::kReload:
    case ControlCommand::Kind::kSchedule:
      if (!kiosk_) return "error: this candela has no kiosk control (scene, brightness, screen)";
      return kiosk_->command(c);
    case ControlCommand::Kind::kPing:
      return "pong";
    case ControlCommand::Kind::kHelp:
      return kControlHelp;
    case ControlCommand::Kind::kError:
      break;
  }
  return "error: " + c.error;
}

void InputHub::input_thread() {
  std::vector<pollfd> fds;
  std::vector<GpioSource*> fd_owner;
  // Scene loads (scene, reload) on a thread of their own: their replies come
  // later, and GPIO and the other clients are served meanwhile.
  std::unique_ptr<SceneCommandWorker> scenes;
  if (control_ && kiosk_) {
    try {
      scenes = std::make_unique<SceneCommandWorker>(*kiosk_);
    } catch (const std::exception& e) {
      LOG_ERROR("%s; scene commands are answered on the input thread", e.what());
    }
  }
  const ControlServer::Answerer answer_fn = [&](std::string_view line,
                                                uint64_t ticket) -> ControlServer::Answer {
    const ControlCommand c = parse_control_command(line, wind_spec_);
    if (scenes && SceneCommandWorker::runs(c)) {
      scenes->submit(ticket, c);
      return {{}, true};
    }
    return {answer_command(c, Origin::kControlSocket)};
  };
  for (;;) {
    const int64_t now = monotonic_ns();
    int64_t deadline = now + GpioSource::kRetryNs;
    for (auto& g : gpio_) deadline = std::min(deadline, g->service(now, *input_sink_));
    if (control_) deadline = std::min(deadline, control_->expire_idle(now));
    fds.clear();
    fd_owner.clear();
    fds.push_back({stop_fd_, POLLIN, 0});
    if (scenes) fds.push_back({scenes->fd(), POLLIN, 0});
    const size_t control_at = fds.size();
    if (control_) control_->add_fds(fds);
    const size_t gpio_at = fds.size();
    for (auto& g : gpio_)
      if (g->fd() >= 0) {
        fds.push_back({g->fd(), POLLIN, 0});
        fd_owner.push_back(g.get());
      }
    const int64_t wait_ns = std::max<int64_t>(0, deadline - monotonic_ns());
    const int timeout_ms = static_cast<int>((wait_ns + 999'999) / 1'000'000);
    const int n = poll(fds.data(), fds.size(), timeout_ms);
    if (n < 0) {
      if (errno == EINTR) continue;
      LOG_ERROR("input: poll: %s; the input thread stops", std::strerror(errno));
      return;
    }
    if (fds[0].revents) return;
    if (n == 0) continue;
    if (scenes && fds[1].revents)
      for (const auto& [ticket, reply] : scenes->take())
        control_->complete(ticket, reply, answer_fn);
    for (size_t i = gpio_at; i < fds.size(); ++i)
      if (fds[i].revents) fd_owner[i - gpio_at]->on_poll(fds[i].revents, *input_sink_);
    if (control_) control_->serve(fds.data() + control_at, gpio_at - control_at, answer_fn);
  }
}

}  // namespace candela
