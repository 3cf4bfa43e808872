// The [mqtt] settings of the kiosk config (parse_mqtt) and what a message
// on PREFIX/set/VERB asks (mqtt_command): no broker, no threads, so the
// config and MQTT fuzz targets take them alone (input/mqtt_bridge.h).
#include <arpa/inet.h>
#include <sys/stat.h>

#include <algorithm>
#include <cstring>

#include "core/error.h"
#include "core/file_read.h"
#include "core/log.h"
#include "input/control_channel.h"
#include "input/mqtt_bridge.h"
#include "params/params.h"

namespace candela {
namespace {

bool topic_level_char(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
         c == '-';
}

bool printable_word(const std::string& s, size_t max) {
  if (s.empty() || s.size() > max) return false;
  for (char c : s)
    if (static_cast<unsigned char>(c) <= 0x20 || c == 0x7f) return false;
  return true;
}

}  // namespace

// "a/b-c/d_e": 1..128 characters, levels of [A-Za-z0-9_-], none empty
// (no wildcards, no leading or trailing '/').
bool mqtt_valid_topic_prefix(const std::string& p) {
  if (p.empty() || p.size() > 128 || p.front() == '/' || p.back() == '/') return false;
  for (size_t i = 0; i < p.size(); ++i) {
    if (p[i] == '/') {
      if (p[i + 1] == '/') return false;
    } else if (!topic_level_char(p[i])) {
      return false;
    }
  }
  return true;
}

std::string mqtt_node_id(const std::string& prefix) {
  std::string id = prefix;
  std::replace(id.begin(), id.end(), '/', '_');
  return id;
}

MqttSettings parse_mqtt(ParamReader& r, bool present) {
  MqttSettings s;
  s.enabled = present && r.boolean("enabled", true);
  if (!present) {
    r.finish();
    return s;
  }
  if (!r.has("host"))
    r.fail("host", "missing; expected the broker's host name or address, e.g. \"127.0.0.1\"");
  s.host = r.string("host", "");
  bool host_ok = !s.host.empty() && s.host.size() <= 253;
  for (char c : s.host) host_ok = host_ok && (topic_level_char(c) || c == '.' || c == ':');
  // An address with ':' is IPv6 as inet_pton reads it (":::" is none); a
  // name is dot-separated labels of 1..63 characters.
  if (host_ok && s.host.find(':') != std::string::npos) {
    in6_addr a6{};
    host_ok = inet_pton(AF_INET6, s.host.c_str(), &a6) == 1;
  } else if (host_ok) {
    size_t label = 0;
    for (char c : s.host + ".") {
      if (c != '.') {
        ++label;
        continue;
      }
      host_ok = host_ok && label >= 1 && label <= 63;
      label = 0;
    }
  }
  if (!host_ok)
    r.fail("host",
           "expected a host name or address of 1..253 characters (letters, digits, '.', '-', "
           "'_', ':'), got \"" +
               echo_value(s.host) + "\"");
  s.tls = r.boolean("tls", false);
  s.port = static_cast<int>(r.integer("port", s.tls ? 8883 : s.port, 1, 65535));
  for (auto [key, field] : {std::pair{"ca_file", &s.ca_file}, std::pair{"cert_file", &s.cert_file},
                            std::pair{"key_file", &s.key_file}}) {
    if (!r.has(key)) continue;
    if (!s.tls) r.fail(key, "given without tls = true; expected [mqtt] tls = true too");
    *field = r.path(key);  // a readable regular file, or ParamReader says so
  }
  if (s.cert_file.empty() != s.key_file.empty())
    r.fail(s.cert_file.empty() ? "key_file" : "cert_file",
           "expected cert_file and key_file together (a client certificate and its key)");
  for (auto [key, field] : {std::pair{"ca_file", &s.ca_file}, std::pair{"cert_file", &s.cert_file},
                            std::pair{"key_file", &s.key_file}}) {
    if (field->empty()) continue;
    // PEM, as libmosquitto's OpenSSL reads it: a file of something else
    // passed --check and failed only at the first connection.
    std::string pem;
    try {
      pem = BoundedFile::open(*field, FileKind::kScene).read_all();
    } catch (const ConfigError& e) {
      r.fail(key, std::string("cannot be read: ") + e.what());
    }
    const char* begin =
        std::string_view(key) == "key_file" ? "-----BEGIN " : "-----BEGIN CERTIFICATE-----";
    if (pem.find(begin) == std::string::npos)
      r.fail(key, std::string("expected a PEM file (a \"") + begin +
                      "\" block), got a file without one");
  }
  s.prefix = r.string("prefix", s.prefix);
  if (!mqtt_valid_topic_prefix(s.prefix))
    r.fail("prefix",
           "expected a topic prefix of 1..128 characters: levels of letters, digits, '_' and "
           "'-' joined by '/' (no wildcards, no empty level), got \"" +
               echo_value(s.prefix) + "\"");
  s.client_id = r.string("client_id", "");
  if (r.has("client_id") && !printable_word(s.client_id, 64))
    r.fail("client_id", "expected 1..64 printable characters without spaces");
  if (s.client_id.empty()) s.client_id = "candela-" + mqtt_node_id(s.prefix);
  s.username = r.string("username", "");
  if (r.has("username") && !printable_word(s.username, 128))
    r.fail("username", "expected 1..128 printable characters without spaces");
  if (r.has("password_file")) {
    if (s.username.empty())
      r.fail("password_file", "given without a username; expected [mqtt] username too");
    const std::string path = r.path("password_file");
    std::string text;
    try {
      text = BoundedFile::open(path, FileKind::kScene).read_all();
    } catch (const ConfigError& e) {
      r.fail("password_file", std::string("cannot be read: ") + e.what());
    }
    if (text.size() > 1024)
      r.fail("password_file", "expected a file of at most 1 KiB (the password on its first line)");
    text = text.substr(0, text.find('\n'));
    if (!text.empty() && text.back() == '\r') text.pop_back();
    if (text.empty())
      r.fail("password_file", "expected the password on the file's first line; it is empty");
    for (char c : text)
      if (static_cast<unsigned char>(c) < 0x20)
        r.fail("password_file", "expected a password without control characters");
    s.password = text;
    struct stat st {};
    if (stat(path.c_str(), &st) == 0 && (st.st_mode & 077))
      LOG_WARN("%s: mqtt.password_file %s can be read by others (mode %03o); chmod 600 it",
               r.file().c_str(), path.c_str(), static_cast<unsigned>(st.st_mode & 0777));
  }
  s.keepalive_s = static_cast<int>(r.integer("keepalive", s.keepalive_s, 5, 3600));
  s.reconnect_max_s = static_cast<int>(r.integer("reconnect_max", s.reconnect_max_s, 1, 300));
  s.discovery = r.boolean("discovery", s.discovery);
  s.discovery_prefix = r.string("discovery_prefix", s.discovery_prefix);
  if (!mqtt_valid_topic_prefix(s.discovery_prefix))
    r.fail("discovery_prefix",
           "expected a topic prefix (levels of letters, digits, '_' and '-' joined by '/'), got "
           "\"" +
               echo_value(s.discovery_prefix) + "\"");
  r.finish();
  return s;
}

MqttCommand mqtt_command(std::string_view set_prefix, std::string_view verb,
                         std::string_view payload, bool retain,
                         const std::vector<std::string>& scenes) {
  MqttCommand c;
  bool ok = !verb.empty() && verb.size() <= 32 && payload.size() <= ControlServer::kMaxLine;
  for (char ch : verb) ok = ok && ch >= 'a' && ch <= 'z';
  for (char ch : payload) ok = ok && static_cast<unsigned char>(ch) >= 0x20;
  if (!ok) {
    c.refusal = "error: expected " + std::string(set_prefix) +
                "COMMAND (lower-case letters) with the arguments as a one-line payload of at "
                "most " +
                std::to_string(ControlServer::kMaxLine) + " bytes";
  } else if (retain && (verb == "gust" || verb == "blowout" || verb == "reload")) {
    // A retained command comes again at every (re)connect: a setting (volume,
    // screen, scene...) is the home's wish and is applied again; an event is
    // not, or every reconnect would blow a gust or reload.
    c.refusal = "error: " + std::string(verb) +
                ": a retained message is not acted on (an event would repeat at every "
                "reconnect); publish it without retain";
  } else if (verb == "scene" && !payload.empty() &&
             std::find(scenes.begin(), scenes.end(), payload) == scenes.end()) {
    // A network client names a scene, never a file: a path would let it
    // probe which files exist and read parse errors quoting them, and make
    // the kiosk load whatever the path holds (issue 34). Files are the
    // owner's: the config, --scene, the local control socket.
    std::string names;
    for (const auto& n : scenes) names += (names.empty() ? "" : ", ") + n;
    c.refusal = "error: scene: over MQTT expected one of the scenes offered (" + names +
                "); a file is named in the kiosk's config or on its control socket";
  } else {
    // The control socket's one parser and handling: "volume" + " 0.4".
    c.line = verb;
    if (!payload.empty()) c.line += ' ';
    c.line.append(payload);
  }
  return c;
}

}  // namespace candela
