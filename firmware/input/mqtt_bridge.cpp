#include "input/mqtt_bridge.h"

#include <mosquitto.h>
#include <mqtt_protocol.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>

#include "core/json_parse.h"
#include "core/log.h"
#include "input/control_channel.h"
#include "input/input_event.h"
#include "input/input_hub.h"

namespace candela {
namespace {
std::once_flag g_lib_once;
}  // namespace

MqttBridge::MqttBridge(MqttSettings settings, InputHub& hub) : s_(std::move(settings)), hub_(hub) {}

MqttBridge::~MqttBridge() { stop(); }

void MqttBridge::start() {
  std::call_once(g_lib_once, [] { mosquitto_lib_init(); });
  mosq_ = mosquitto_new(s_.client_id.c_str(), true, this);
  if (!mosq_) {
    LOG_ERROR("mqtt: cannot create a libmosquitto client (%s); running without MQTT",
              std::strerror(errno));
    return;
  }
  if (!s_.username.empty())
    mosquitto_username_pw_set(mosq_, s_.username.c_str(),
                              s_.password.empty() ? nullptr : s_.password.c_str());
  if (s_.tls) {
    // The broker's name is checked against its certificate (never insecure).
    const int rc = mosquitto_tls_set(mosq_, s_.ca_file.empty() ? nullptr : s_.ca_file.c_str(),
                                     s_.ca_file.empty() ? "/etc/ssl/certs" : nullptr,
                                     s_.cert_file.empty() ? nullptr : s_.cert_file.c_str(),
                                     s_.key_file.empty() ? nullptr : s_.key_file.c_str(), nullptr);
    if (rc != MOSQ_ERR_SUCCESS) {
      LOG_ERROR("mqtt: cannot set up TLS (%s); running without MQTT", mosquitto_strerror(rc));
      mosquitto_destroy(mosq_);
      mosq_ = nullptr;
      return;
    }
  }
  // Small messages, answered at once: no Nagle delay (40 ms with delayed ACKs).
  mosquitto_int_option(mosq_, MOSQ_OPT_TCP_NODELAY, 1);
  // MQTT v5, for its Maximum Packet Size: the broker then drops a message to
  // us larger than any command, instead of libmosquitto reading all of it
  // (a 200 MB payload took 390 MB) before the 1 KiB line limit could refuse
  // it (issue 34). libmosquitto keeps CONNECT properties only from
  // mosquitto_connect_bind_v5(), which connects blocking; called with port -1
  // it stores them and refuses at once (MOSQ_ERR_INVAL), and the async
  // connects in run() send them (tests/input/mqtt_cli.py huge checks it).
  mosquitto_int_option(mosq_, MOSQ_OPT_PROTOCOL_VERSION, MQTT_PROTOCOL_V5);
  mosquitto_property* props = nullptr;
  mosquitto_property_add_int32(&props, MQTT_PROP_MAXIMUM_PACKET_SIZE, kMaxPacketBytes);
  const int seeded =
      mosquitto_connect_bind_v5(mosq_, s_.host.c_str(), -1, s_.keepalive_s, nullptr, props);
  mosquitto_property_free_all(&props);
  if (seeded != MOSQ_ERR_INVAL)
    LOG_WARN("mqtt: could not set the maximum packet size (%s)", mosquitto_strerror(seeded));
  const std::string avail = s_.prefix + "/availability";
  mosquitto_will_set(mosq_, avail.c_str(), 7, "offline", 1, true);
  mosquitto_connect_callback_set(mosq_, [](mosquitto*, void* self, int rc) {
    static_cast<MqttBridge*>(self)->on_connect(rc);
  });
  mosquitto_disconnect_callback_set(mosq_, [](mosquitto*, void* self, int rc) {
    static_cast<MqttBridge*>(self)->on_disconnect(rc);
  });
  mosquitto_message_callback_set(mosq_, [](mosquitto*, void* self, const mosquitto_message* m) {
    static_cast<MqttBridge*>(self)->on_message(m);
  });
  mosquitto_log_callback_set(mosq_, [](mosquitto*, void* self, int level, const char* text) {
    if (level == MOSQ_LOG_ERR && text) static_cast<MqttBridge*>(self)->last_lib_error_ = text;
  });
  LOG_INFO("mqtt: broker %s:%d%s, topics %s/...", s_.host.c_str(), s_.port, s_.tls ? " (TLS)" : "",
           s_.prefix.c_str());
  thread_ = std::thread([this] { run(); });
}

void MqttBridge::stop() {
  {
    std::lock_guard lock(mu_);
    stop_.store(true, std::memory_order_release);
  }
  cv_.notify_all();
  if (thread_.joinable()) thread_.join();
  if (mosq_) mosquitto_destroy(mosq_);
  mosq_ = nullptr;
}

bool MqttBridge::wait_stop(int64_t ms) {
  std::unique_lock lock(mu_);
  return cv_.wait_for(lock, std::chrono::milliseconds(ms),
                      [&] { return stop_.load(std::memory_order_acquire); });
}

void MqttBridge::publish(const std::string& topic, const std::string& payload, bool retain,
                         int qos) {
  mosquitto_publish(mosq_, nullptr, topic.c_str(), static_cast<int>(payload.size()), payload.data(),
                    qos, retain);
}

bool MqttStatePacer::due(const std::string& state, int64_t now_ns, bool refresh) {
  std::string settings = state, moving;
  if (std::optional<nlohmann::json> j = try_parse_json(state, nullptr); j && j->is_object()) {
    for (const char* k : {"wind", "events"})
      if (auto it = j->find(k); it != j->end()) moving += it->dump();
    for (const char* k : {"frame", "step", "fps", "wind", "events"}) j->erase(k);
    settings = j->dump();
  }
  const bool settings_changed = !any_ || settings != settings_;
  const bool moved = moving != moving_ && now_ns - published_ns_ >= kMovingIntervalNs;
  if (!refresh && !settings_changed && !moved) return false;
  settings_ = std::move(settings);
  moving_ = std::move(moving);
  published_ns_ = now_ns;
  any_ = true;
  return true;
}

// Paced by MqttStatePacer: a command's answer (force) and the 10 s refresh
// always go out.
void MqttBridge::publish_state(bool force) {
  const std::string state = hub_.summary_json();
  if (!pacer_.due(state, monotonic_ns(), force)) return;
  // QoS 0: the next state supersedes it, and no PUBACK comes back to be
  // held by the broker's Nagle (a command would then wait about 40 ms).
  publish(s_.prefix + "/state", state, true, 0);
}

std::string MqttBridge::discovery_json(Entity entity) const {
  using Json = nlohmann::ordered_json;
  const std::string node = mqtt_node_id(s_.prefix);
  const std::string& p = s_.prefix;
  Json j;
  if (entity == Entity::kScreen) {  // a switch: the screen on or off
    j["name"] = "Screen";
    j["unique_id"] = node + "_screen";
    j["object_id"] = node + "_screen";
    j["command_topic"] = p + "/set/screen";
    j["state_topic"] = p + "/state";
    j["value_template"] = "{{ value_json.screen }}";
    j["payload_on"] = "on";
    j["payload_off"] = "off";
    j["state_on"] = "on";
    j["state_off"] = "off";
    j["icon"] = "mdi:fireplace";
  } else if (entity == Entity::kBrightness) {  // a number: the master brightness
    j["name"] = "Brightness";
    j["unique_id"] = node + "_brightness";
    j["object_id"] = node + "_brightness";
    j["command_topic"] = p + "/set/brightness";
    j["state_topic"] = p + "/state";
    j["value_template"] = "{{ value_json.brightness }}";
    j["min"] = 0;
    j["max"] = 1;
    j["step"] = 0.01;
    j["mode"] = "slider";
    j["icon"] = "mdi:brightness-6";
  } else if (entity == Entity::kScene) {  // a select: the built-in scenes
    j["name"] = "Scene";
    j["unique_id"] = node + "_scene";
    j["object_id"] = node + "_scene";
    j["command_topic"] = p + "/set/scene";
    j["state_topic"] = p + "/state";
    j["value_template"] = "{{ value_json.scene }}";
    j["options"] = s_.scenes;
    j["icon"] = "mdi:candle";
  } else if (entity ==
             Entity::kGust) {  // a button: a gust from the front at the scene's [wind] gust_speed
    j["name"] = "Gust";
    j["unique_id"] = node + "_gust";
    j["object_id"] = node + "_gust";
    j["command_topic"] = p + "/set/gust";
    j["payload_press"] = "front";
    j["icon"] = "mdi:weather-windy";
  } else {
    j["name"] = "Volume";
    j["unique_id"] = node + "_volume";
    j["object_id"] = node + "_volume";
    j["command_topic"] = p + "/set/volume";
    j["state_topic"] = p + "/state";
    j["value_template"] = "{{ value_json.volume }}";
    j["min"] = 0;
    j["max"] = 1;
    j["step"] = 0.01;
    j["mode"] = "slider";
    j["icon"] = "mdi:volume-high";
  }
  j["availability_topic"] = p + "/availability";
  j["payload_available"] = "online";
  j["payload_not_available"] = "offline";
  j["device"] = {{"identifiers", {"candela_" + node}},
                 {"name", "Candela " + p},
                 {"manufacturer", "Candela"},
                 {"model", "candela"},
                 {"sw_version", "0.1.0"}};
  return j.dump(-1, ' ', false, Json::error_handler_t::replace);
}

namespace {
// A CONNACK's v5 reason code, worded as mosquitto_connack_string() words the
// v3 ones ("not authorised" reads the same either way).
std::string refusal_text(int rc) {
  if (rc == MQTT_RC_BAD_USERNAME_OR_PASSWORD || rc == MQTT_RC_NOT_AUTHORIZED)
    return std::string("not authorised (") + mosquitto_reason_string(rc) + ")";
  return mosquitto_reason_string(rc);
}
}  // namespace

void MqttBridge::on_connect(int rc) {
  if (rc != 0) {
    // Refused: a wrong password, an unknown client... said once per reason.
    if (rc != last_refusal_)
      LOG_ERROR(
          "mqtt: broker %s:%d refused the connection: %s%s; retrying with backoff (the display "
          "runs on)",
          s_.host.c_str(), s_.port, refusal_text(rc).c_str(),
          rc == MQTT_RC_BAD_USERNAME_OR_PASSWORD || rc == MQTT_RC_NOT_AUTHORIZED
              ? " (check [mqtt] username and password_file)"
              : "");
    last_refusal_ = rc;
    refused_ = true;
    reported_ = true;
    connected_ = false;
    return;
  }
  connected_ = true;
  last_refusal_ = 0;
  connects_.fetch_add(1, std::memory_order_relaxed);
  LOG_INFO("mqtt: connected to %s:%d%s", s_.host.c_str(), s_.port, reported_ ? " again" : "");
  reported_ = false;
  const std::string sub = s_.prefix + "/set/+";
  mosquitto_subscribe(mosq_, nullptr, sub.c_str(), 1);
  if (s_.room.enabled) {
    const std::string room = s_.room.topic + "/gust";
    mosquitto_subscribe(mosq_, nullptr, room.c_str(), 0);
  }
  publish(s_.prefix + "/availability", "online", true);
  if (s_.discovery) {
    const std::string node = mqtt_node_id(s_.prefix);
    const std::string d = s_.discovery_prefix;
    publish(d + "/number/" + node + "/volume/config", discovery_json(Entity::kVolume), true);
    publish(d + "/button/" + node + "/gust/config", discovery_json(Entity::kGust), true);
    publish(d + "/switch/" + node + "/screen/config", discovery_json(Entity::kScreen), true);
    publish(d + "/number/" + node + "/brightness/config", discovery_json(Entity::kBrightness),
            true);
    if (!s_.scenes.empty())
      publish(d + "/select/" + node + "/scene/config", discovery_json(Entity::kScene), true);
  }
  publish_state(true);
}

void MqttBridge::on_disconnect(int rc) {
  if (connected_ && rc != 0 && !reported_) {
    LOG_WARN("mqtt: lost the broker %s:%d (%s); reconnecting with backoff", s_.host.c_str(),
             s_.port, mosquitto_strerror(rc));
    reported_ = true;
  }
  connected_ = false;
}

void MqttBridge::on_message(const mosquitto_message* m) {
  if (s_.room.enabled && m->topic && s_.room.topic.size() + 5 == std::strlen(m->topic) &&
      std::strncmp(m->topic, s_.room.topic.c_str(), s_.room.topic.size()) == 0 &&
      std::strcmp(m->topic + s_.room.topic.size(), "/gust") == 0) {
    on_room_message(m);
    return;
  }
  const std::string set = s_.prefix + "/set/";
  if (!m->topic || std::strncmp(m->topic, set.c_str(), set.size()) != 0) return;
  const std::string verb = m->topic + set.size();
  const std::string_view payload(static_cast<const char*>(m->payload),
                                 m->payloadlen > 0 ? static_cast<size_t>(m->payloadlen) : 0);
  const MqttCommand c = mqtt_command(set, verb, payload, m->retain, s_.scenes);
  const std::string reply =
      c.refusal.empty() ? hub_.answer(c.line, InputHub::Origin::kMqtt) : c.refusal;
  commands_.fetch_add(1, std::memory_order_relaxed);
  publish(s_.prefix + "/reply", reply, false, 0);
  publish_state(true);
}

void MqttBridge::on_room_message(const mosquitto_message* m) {
  const std::string_view payload(static_cast<const char*>(m->payload),
                                 m->payloadlen > 0 ? static_cast<size_t>(m->payloadlen) : 0);
  std::string error;
  const std::optional<RoomGust> g = parse_room_gust(payload, &error);
  const int64_t mono = monotonic_ns();
  if (!g) {
    // Logged, dropped; at most one line per 10 s (a broken sender cannot
    // flood the log).
    hub_.room_note(InputHub::RoomNote::kInvalid);
    if (room_invalid_logged_ == 0 || mono - room_invalid_logged_ >= 10'000'000'000) {
      LOG_WARN("mqtt: room: dropped a message on %s: %s%s", m->topic, error.c_str(),
               room_invalid_quiet_ ? " (and others since, not logged)" : "");
      room_invalid_logged_ = mono;
      room_invalid_quiet_ = 0;
    } else {
      ++room_invalid_quiet_;
    }
    return;
  }
  if (g->origin == s_.client_id) {  // our own, back from the broker
    hub_.room_note(InputHub::RoomNote::kOwn);
    return;
  }
  hub_.room_note(InputHub::RoomNote::kReceived);
  const WindSpec& wind = hub_.wind_spec();
  const WindTravel t = room_travel(wind, *g, s_.room.x, s_.room.z);
  if (!t.reached) {
    hub_.room_note(InputHub::RoomNote::kUpwind);
    LOG_DEBUG("room: gust %s#%llu from [%g, %g] blows away from here [%g, %g]; not reached",
              g->origin.c_str(), static_cast<unsigned long long>(g->seq), g->px, g->pz, s_.room.x,
              s_.room.z);
    return;
  }
  const auto delay_ns = static_cast<int64_t>(std::llround(t.delay.to_double() * 1e9));
  const int64_t due_ns = g->t_ns + delay_ns;
  const int64_t received_ns = realtime_ns();
  int64_t lead = due_ns - received_ns;
  if (lead > 120'000'000'000) {
    hub_.room_note(InputHub::RoomNote::kInvalid);
    LOG_WARN("mqtt: room: dropped gust %s#%llu due %.1f s from now (clocks apart? run NTP)",
             g->origin.c_str(), static_cast<unsigned long long>(g->seq),
             static_cast<double>(lead) / 1e9);
    return;
  }
  if (lead < 0) {
    hub_.room_note(InputHub::RoomNote::kLate);
    // Older than a whole gust: stale (a backlog after a reconnect).
    if (-lead > static_cast<int64_t>(wind.gust_seconds.to_double() * 1e9)) {
      LOG_DEBUG("room: gust %s#%llu came %.1f ms after its time, longer than a gust; dropped",
                g->origin.c_str(), static_cast<unsigned long long>(g->seq),
                static_cast<double>(-lead) / 1e6);
      return;
    }
    LOG_DEBUG(
        "room: gust %s#%llu came %.1f ms after its time (broker round trip); started at "
        "once",
        g->origin.c_str(), static_cast<unsigned long long>(g->seq),
        static_cast<double>(-lead) / 1e6);
    lead = 0;
  }
  InputHub::RoomIn in;
  in.wind.type = g->type;
  in.wind.x = Fixed::from_double(g->x) * t.gain;
  in.wind.z = Fixed::from_double(g->z) * t.gain;
  in.due_mono_ns = mono + lead;
  in.origin_ns = g->t_ns;
  in.received_ns = received_ns;
  in.due_ns = due_ns;
  if (!hub_.give_room_gust(in)) {
    LOG_WARN("mqtt: room: the frame loop's room queue is full; gust %s#%llu dropped",
             g->origin.c_str(), static_cast<unsigned long long>(g->seq));
    return;
  }
  LOG_INFO(
      "room: gust %s#%llu from [%g, %g], %.2f m upwind of here: due at +%.1f ms (in %.1f ms), "
      "strength x%.3f",
      g->origin.c_str(), static_cast<unsigned long long>(g->seq), g->px, g->pz,
      t.distance.to_double(), static_cast<double>(delay_ns) / 1e6, static_cast<double>(lead) / 1e6,
      t.gain.to_double());
}

void MqttBridge::publish_room() {
  InputHub::RoomOut out;
  while (hub_.take_room_gust(out)) {
    // Not connected, or stuck long enough that it would come stale: dropped.
    if (!connected_ || realtime_ns() - out.t_ns > 2'000'000'000) {
      LOG_DEBUG("room: a gust started here was not published (%s)",
                connected_ ? "too old" : "not connected");
      continue;
    }
    RoomGust g;
    g.origin = s_.client_id;
    g.seq = ++room_seq_;
    g.t_ns = out.t_ns;
    g.type = out.wind.type;
    g.x = out.wind.x.to_double();
    g.z = out.wind.z.to_double();
    g.px = s_.room.x;
    g.pz = s_.room.z;
    publish(s_.room.topic + "/gust", room_gust_json(g), false, 0);
    hub_.room_note(InputHub::RoomNote::kSent);
  }
}

std::string MqttBridge::failure(int rc) const {
  // libmosquitto's "A TLS error occurred." hides OpenSSL's reason
  // (certificate verify failed...): its last error log line says it.
  if (rc == MOSQ_ERR_TLS && !last_lib_error_.empty())
    return "TLS: " + last_lib_error_ +
           " (check [mqtt] ca_file, and that host is the name in the broker's certificate)";
  return rc == MOSQ_ERR_ERRNO ? std::strerror(errno) : mosquitto_strerror(rc);
}

void MqttBridge::run() {
  int64_t backoff_ms = 1000;
  const int64_t max_ms = int64_t{s_.reconnect_max_s} * 1000;
  bool socket_up = false;
  int64_t last_check = 0, last_refresh = 0, connecting_since = 0;
  while (!stop_.load(std::memory_order_acquire)) {
    if (!socket_up) {
      const int rc = mosquitto_connect_async(mosq_, s_.host.c_str(), s_.port, s_.keepalive_s);
      if (rc != MOSQ_ERR_SUCCESS) {
        if (!reported_)
          LOG_WARN(
              "mqtt: cannot reach the broker %s:%d (%s); retrying with backoff (the display "
              "runs on)",
              s_.host.c_str(), s_.port, failure(rc).c_str());
        reported_ = true;
        wait_stop(backoff_ms);
        backoff_ms = std::min(max_ms, backoff_ms * 2);
        continue;
      }
      socket_up = true;
      connecting_since = monotonic_ns();
    }
    // With a room, a gust started here waits at most 5 ms to be published.
    int rc = mosquitto_loop(mosq_, s_.room.enabled ? 5 : 100, 1);
    if (s_.room.enabled) publish_room();
    // Something on the port that never answers like a broker: give up on
    // it after the keepalive, as libmosquitto would on a silent broker.
    if (rc == MOSQ_ERR_SUCCESS && !connected_ && !refused_ &&
        monotonic_ns() - connecting_since > int64_t{s_.keepalive_s} * 1'000'000'000)
      rc = MOSQ_ERR_KEEPALIVE;
    if (rc != MOSQ_ERR_SUCCESS || refused_) {
      refused_ = false;
      if (!reported_)
        LOG_WARN("mqtt: broker %s:%d: %s; retrying with backoff (the display runs on)",
                 s_.host.c_str(), s_.port, failure(rc).c_str());
      reported_ = true;
      connected_ = false;
      socket_up = false;
      mosquitto_disconnect(mosq_);
      wait_stop(backoff_ms);
      backoff_ms = std::min(max_ms, backoff_ms * 2);
      continue;
    }
    if (!connected_) continue;
    backoff_ms = 1000;
    const int64_t now = monotonic_ns() / 1'000'000;
    if (now - last_check >= 100) {
      last_check = now;
      const bool refresh = now - last_refresh >= 10'000;
      if (refresh) last_refresh = now;
      publish_state(refresh);
    }
  }
  if (connected_) {
    publish(s_.prefix + "/availability", "offline", true);
    mosquitto_disconnect(mosq_);
    for (int i = 0; i < 20 && mosquitto_loop(mosq_, 50, 1) == MOSQ_ERR_SUCCESS; ++i) {
    }
  }
}

}  // namespace candela
