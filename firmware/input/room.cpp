#include "input/room.h"

#include <time.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "core/json_parse.h"
#include "input/mqtt_bridge.h"
#include "params/params.h"

namespace candela {

RoomSettings parse_room(ParamReader& r, bool present, bool mqtt) {
  RoomSettings s;
  s.enabled = present && r.boolean("enabled", true);
  if (!present) {
    r.finish();
    return s;
  }
  if (s.enabled && !mqtt)
    r.fail("position",
           "given without [mqtt]; expected an [mqtt] table too (the broker the room's displays "
           "share)");
  if (!r.has("position"))
    r.fail("position",
           "missing; expected where this display stands, [x, z] in metres, e.g. [1.5, 0]");
  const std::vector<double> p = r.numbers("position", -100, 100, 2);
  if (p.size() != 2)
    r.fail("position", "expected [x, z]: 2 numbers in metres within +-100, got " +
                           std::to_string(p.size()) + " number(s)");
  s.x = p[0];
  s.z = p[1];
  s.topic = r.string("topic", s.topic);
  if (!mqtt_valid_topic_prefix(s.topic))
    r.fail("topic",
           "expected a topic of 1..128 characters: levels of letters, digits, '_' and '-' joined "
           "by '/' (no wildcards, no empty level), got \"" +
               echo_value(s.topic) + "\"");
  r.finish();
  return s;
}

std::string room_gust_json(const RoomGust& g) {
  using Json = nlohmann::ordered_json;
  Json j;
  j["v"] = 1;
  j["origin"] = g.origin;
  j["seq"] = g.seq;
  j["t_ns"] = g.t_ns;
  j["type"] = g.type == WindEvent::Type::kBlowOut ? "blowout" : "gust";
  j["x"] = g.x;
  j["z"] = g.z;
  j["position"] = {g.px, g.pz};
  return j.dump(-1, ' ', false, Json::error_handler_t::replace);
}

namespace {
bool finite_in(const nlohmann::json& v, double limit, double* out) {
  if (!v.is_number()) return false;
  const double d = v.get<double>();
  if (!std::isfinite(d) || std::fabs(d) > limit) return false;
  *out = d;
  return true;
}
}  // namespace

std::optional<RoomGust> parse_room_gust(std::string_view payload, std::string* error) {
  auto bad = [&](std::string why) -> std::optional<RoomGust> {
    if (error) *error = std::move(why);
    return std::nullopt;
  };
  if (payload.size() > RoomGust::kMaxMessage)
    return bad("expected at most " + std::to_string(RoomGust::kMaxMessage) + " bytes, got " +
               std::to_string(payload.size()));
  std::string json_error;
  const std::optional<nlohmann::json> parsed = try_parse_json(payload, &json_error);
  if (!parsed) return bad("expected JSON: " + json_error);
  const nlohmann::json& j = *parsed;
  if (!j.is_object()) return bad("expected a JSON object");
  auto field = [&](const char* key) -> const nlohmann::json* {
    const auto it = j.find(key);
    return it == j.end() ? nullptr : &*it;
  };
  const nlohmann::json* v = field("v");
  if (!v || !v->is_number_integer() || v->get<int64_t>() != 1)
    return bad("v: expected 1 (the message version)");
  RoomGust g;
  const nlohmann::json* origin = field("origin");
  if (!origin || !origin->is_string()) return bad("origin: expected the sender's client id");
  g.origin = origin->get<std::string>();
  bool printable = !g.origin.empty() && g.origin.size() <= 64;
  for (char c : g.origin)
    printable = printable && static_cast<unsigned char>(c) > 0x20 && c != 0x7f;
  if (!printable) return bad("origin: expected 1..64 printable characters without spaces");
  const nlohmann::json* seq = field("seq");
  if (!seq || !seq->is_number_unsigned()) return bad("seq: expected a whole number >= 0");
  g.seq = seq->get<uint64_t>();
  const nlohmann::json* t = field("t_ns");
  if (!t || !t->is_number_integer() || t->get<int64_t>() <= 0)
    return bad("t_ns: expected the origin's CLOCK_REALTIME in ns, a whole number > 0");
  g.t_ns = t->get<int64_t>();
  const nlohmann::json* type = field("type");
  if (!type || !type->is_string() ||
      (type->get<std::string>() != "gust" && type->get<std::string>() != "blowout"))
    return bad("type: expected \"gust\" or \"blowout\"");
  g.type =
      type->get<std::string>() == "blowout" ? WindEvent::Type::kBlowOut : WindEvent::Type::kGust;
  const nlohmann::json* x = field("x");
  const nlohmann::json* z = field("z");
  if (!x || !finite_in(*x, 100, &g.x)) return bad("x: expected a number in m/s within +-100");
  if (!z || !finite_in(*z, 100, &g.z)) return bad("z: expected a number in m/s within +-100");
  const nlohmann::json* p = field("position");
  if (!p || !p->is_array() || p->size() != 2 || !finite_in((*p)[0], 100, &g.px) ||
      !finite_in((*p)[1], 100, &g.pz))
    return bad("position: expected [x, z], 2 numbers in metres within +-100");
  return g;
}

WindTravel room_travel(const WindSpec& spec, const RoomGust& g, double x, double z) {
  return WindField::travel(spec, {Fixed::from_double(g.px), Fixed::from_double(g.pz)},
                           {Fixed::from_double(x), Fixed::from_double(z)}, Fixed::from_double(g.x),
                           Fixed::from_double(g.z));
}

int64_t realtime_ns() {
  timespec ts{};
  clock_gettime(CLOCK_REALTIME, &ts);
  return int64_t{ts.tv_sec} * 1'000'000'000 + ts.tv_nsec;
}

}  // namespace candela
