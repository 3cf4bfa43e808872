// libFuzzer target for what arrives over MQTT (issue 34): a message on
// PREFIX/set/VERB (input/mqtt_bridge.h's mqtt_command, then the control
// socket's parser) or a room gust (room.h's parse_room_gust, then its travel
// to this display). Input: a flag byte (bit 0: retained; bit 1: a room
// gust), then VERB up to the first '\n', then the payload. What must hold:
// a network client never names a file (an accepted `scene` is one of the
// offered names), an event (gust, blowout, reload) is never taken from a
// retained message, a refusal is bounded; a room gust that parses is within
// its limits and reaches here after a finite, bounded delay.
//   build with clang: ninja -C build-fuzz mqtt_command_fuzz (tests/fuzz/run-fuzz.sh)
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "input/control_channel.h"
#include "input/mqtt_bridge.h"
#include "input/room.h"
#include "wind/wind_field.h"

namespace candela::noise_tables {
std::string_view find(std::string_view) { return {}; }
}  // namespace candela::noise_tables

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace candela;
  if (size < 1) return 0;
  const bool retained = data[0] & 1, room = data[0] & 2;
  const std::string_view in(reinterpret_cast<const char*>(data + 1), size - 1);
  static const WindSpec spec;
  if (room) {
    std::string error;
    const std::optional<RoomGust> g = parse_room_gust(in, &error);
    if (!g) {
      if (error.empty() || error.size() > 400) __builtin_trap();
      return 0;
    }
    if (in.size() > RoomGust::kMaxMessage || g->origin.empty() || g->origin.size() > 64 ||
        !(std::hypot(g->x, g->z) <= 100.0 * std::sqrt(2.0)) || !std::isfinite(g->px) ||
        !std::isfinite(g->pz))
      __builtin_trap();
    const WindTravel t = room_travel(spec, *g, 1.5, -2.0);
    if (t.reached && (t.delay < Fixed{} || t.gain < Fixed{} || t.gain > Fixed::from_int(1)))
      __builtin_trap();
    return 0;
  }
  const size_t nl = in.find('\n');
  const std::string_view verb = in.substr(0, nl), payload = nl == std::string_view::npos
                                                                ? std::string_view()
                                                                : in.substr(nl + 1);
  static const std::vector<std::string> offered = {"default", "eigen-candle", "eigen-fireplace"};
  const MqttCommand c = mqtt_command("home/candela/set/", verb, payload, retained, offered);
  if (c.line.empty() == c.refusal.empty()) __builtin_trap();  // one or the other
  if (!c.refusal.empty()) {
    if (c.refusal.size() > 400 || c.refusal.rfind("error: ", 0) != 0) __builtin_trap();
    return 0;
  }
  if (retained && (verb == "gust" || verb == "blowout" || verb == "reload")) __builtin_trap();
  if (c.line.size() > 32 + 1 + ControlServer::kMaxLine) __builtin_trap();
  const ControlCommand cmd = parse_control_command(c.line, spec);
  // A network client names a scene, never a file.
  if (cmd.kind == ControlCommand::Kind::kScene &&
      std::find(offered.begin(), offered.end(), cmd.scene) == offered.end())
    __builtin_trap();
  return 0;
}
