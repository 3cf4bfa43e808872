// Home automation over MQTT (issue 18; README "MQTT"): optional, off unless
// the kiosk config has an [mqtt] table. Through libmosquitto (Debian
// libmosquitto-dev), on a thread of its own:
//   PREFIX/set/COMMAND   payload: the command's arguments; routed through the
//                        control socket's parser (InputHub::answer), e.g.
//                        PREFIX/set/volume "0.4", PREFIX/set/gust "left 2";
//                        retained, a setting is applied at every connect but
//                        an event (gust, blowout, reload) is refused
//   PREFIX/reply         what each command answered ("ok", "error: ...")
//   PREFIX/state         retained JSON: volume, wind, candles lit, frame
//                        (InputHub::summary_json), on connect, after each
//                        command and whenever volume/wind/candles change
//   PREFIX/availability  retained "online"; "offline" on exit and as the
//                        last will (the broker sends it if candela vanishes)
//   DISCOVERY/number/NODE/volume/config  Home Assistant discovery: a volume
//                        number entity (slider 0..1) on a "Candela" device,
//   DISCOVERY/button/NODE/gust/config    and a gust button (set/gust "front"),
//   DISCOVERY/switch/NODE/screen/config  the screen on/off (set/screen on|off),
//   DISCOVERY/number/NODE/brightness/config  the master brightness (0..1),
//   DISCOVERY/select/NODE/scene/config   the built-in scenes (set/scene NAME)
// A broker that is absent, refuses the login, goes away or never answers
// (given up after the keepalive) is logged once per outage and retried with
// backoff (1 s doubling to reconnect_max); the frame loop never waits on it
// (it only reads and writes InputHub's atomics). The thread drives
// mosquitto_loop() itself rather than mosquitto_loop_start(): libmosquitto's
// own loop ends for good on a DNS failure (MOSQ_ERR_EAI). Connecting is
// non-blocking; only a host name's DNS lookup can hold the thread (never
// the display).
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include "input/room.h"

struct mosquitto;
struct mosquitto_message;

namespace candela {

class InputHub;
class ParamReader;

struct MqttSettings {
  bool enabled = false;  // the config has an [mqtt] table
  std::string host;      // required
  int port = 1883;
  std::string prefix = "candela";  // topic prefix: levels of [A-Za-z0-9_-], '/'-separated
  std::string client_id;           // empty: "candela-" + the prefix's levels joined by '-'
  std::string username;            // empty: anonymous
  std::string password;            // read from password_file (its first line)
  // TLS (tls = true; the port defaults to 8883 then): the broker's
  // certificate is checked against ca_file (PEM), else the system's CAs
  // (/etc/ssl/certs), and its name against host; a client certificate is
  // cert_file + key_file (both or neither). Paths are checked when read.
  bool tls = false;
  std::string ca_file, cert_file, key_file;
  int keepalive_s = 30;
  int reconnect_max_s = 30;  // the backoff's ceiling
  bool discovery = true;     // publish Home Assistant discovery config
  std::string discovery_prefix = "homeassistant";
  // The scene select's options: the built-in scenes' names (set by the
  // runtime; empty: no scene select).
  std::vector<std::string> scenes;
  // Several screens, one room (input/room.h): the config's [room].
  //   ROOM_TOPIC/gust      JSON (RoomGust): every gust started here, QoS 0,
  //                        not retained; those of the other displays are
  //                        received, scheduled and handed to the frame loop
  RoomSettings room;
};

// Reads [mqtt] (password_file resolved against the config's folder, read
// now: a regular file of at most 1 KiB whose first line is the password).
// Calls reader.finish(). Throws ConfigError naming file, key and what was
// expected.
MqttSettings parse_mqtt(ParamReader& reader, bool present);

// "a/b-c/d_e": 1..128 characters, levels of [A-Za-z0-9_-], none empty (no
// wildcards, no leading or trailing '/').
bool mqtt_valid_topic_prefix(const std::string& prefix);

// Home Assistant's discovery node id for a prefix: '/' -> '_'.
std::string mqtt_node_id(const std::string& prefix);

// When the retained state is published again (issue 34: it went out ~10
// times a second while the wind moved, which a broker and Home Assistant's
// recorder keep): at once when a setting changes (screen, scene,
// brightness, volume, display, candles lit, errors...), at most once a
// second for what moves on its own (the wind, the events count), and every
// `refresh` regardless. The frame counter, step and fps alone never count as
// a change. State texts are InputHub::summary_json()'s.
class MqttStatePacer {
 public:
  static constexpr int64_t kMovingIntervalNs = 1'000'000'000;
  // Whether `state` is to be published at `now_ns`; if so it is taken as published.
  bool due(const std::string& state, int64_t now_ns, bool refresh);

 private:
  std::string settings_, moving_;
  int64_t published_ns_ = 0;
  bool any_ = false;
};

// What a message on PREFIX/set/VERB asks (`set_prefix` = "PREFIX/set/"):
// the control socket's line to answer, or the reply that refuses it. A verb
// of lower-case letters, a one-line payload within the socket's line limit;
// an event (gust, blowout, reload) never from a retained message; a scene
// only by one of `scenes`' names, never a path. No broker, no hub: the MQTT
// fuzz target's way in.
struct MqttCommand {
  std::string line;     // for InputHub::answer; empty when refused
  std::string refusal;  // "error: ..."; empty when accepted
};
MqttCommand mqtt_command(std::string_view set_prefix, std::string_view verb,
                         std::string_view payload, bool retain,
                         const std::vector<std::string>& scenes);

class MqttBridge {
 public:
  MqttBridge(MqttSettings settings, InputHub& hub);
  ~MqttBridge();
  MqttBridge(const MqttBridge&) = delete;
  MqttBridge& operator=(const MqttBridge&) = delete;

  // Starts the client thread (connects in the background). Never throws for
  // network trouble; a libmosquitto that cannot be set up is logged.
  void start();
  // Publishes "offline", disconnects, joins the thread.
  void stop();

  uint64_t connects() const { return connects_.load(std::memory_order_relaxed); }
  uint64_t commands() const { return commands_.load(std::memory_order_relaxed); }

 private:
  void run();
  void on_connect(int rc);
  void on_disconnect(int rc);
  void on_message(const mosquitto_message* m);
  void on_room_message(const mosquitto_message* m);
  void publish_room();  // the gusts started here since the last call
  // The largest MQTT packet the broker may send us (v5 Maximum Packet Size):
  // a command's topic and 1 KiB line with room to spare.
  static constexpr int kMaxPacketBytes = 8192;
  void publish(const std::string& topic, const std::string& payload, bool retain, int qos = 1);
  void publish_state(bool force);
  enum class Entity { kVolume, kGust, kScreen, kBrightness, kScene };
  std::string discovery_json(Entity entity) const;
  bool wait_stop(int64_t ms);
  std::string failure(int rc) const;  // why a connection failed, for the log

  MqttSettings s_;
  std::string last_lib_error_;  // libmosquitto's last error log line (its thread only)
  InputHub& hub_;
  mosquitto* mosq_ = nullptr;
  std::thread thread_;
  std::atomic<bool> stop_{false};
  std::mutex mu_;  // the backoff wait only
  std::condition_variable cv_;
  bool connected_ = false;  // client thread only
  bool reported_ = false;   // an outage already logged (client thread only)
  int last_refusal_ = 0;    // the CONNACK refusal last logged
  bool refused_ = false;    // the last CONNACK refused (client thread only)
  MqttStatePacer pacer_;    // client thread only
  std::atomic<uint64_t> connects_{0}, commands_{0};
  uint64_t room_seq_ = 0;            // client thread only
  int64_t room_invalid_logged_ = 0;  // when a bad room message was last logged
  uint64_t room_invalid_quiet_ = 0;  // bad ones since, not logged
};

}  // namespace candela
