// Several screens, one room (issue 18; README "Several screens, one room"):
// displays that share an MQTT broker and know where they stand share one
// wind field. Optional, off unless the kiosk config has a [room] table (which
// needs [mqtt]):
//   [room]
//   position = [1.5, 0]        # x (left->right), z (toward the viewer), metres
//   topic = "candela/room"     # gusts go to TOPIC/gust (the same on every display)
// A gust started on a display (button, camera, key, control socket, MQTT
// set/gust) is published with its origin's CLOCK_REALTIME time; each other
// display computes with its own [wind] (WindField::travel: the candle paper's
// plane S, the room as the scene) when it reaches it and how much weaker,
// and starts it then in its own wind field. Received gusts are never
// published again; a display ignores its own.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "wind/wind_field.h"

namespace candela {

class ParamReader;

struct RoomSettings {
  bool enabled = false;  // the config has a [room] table
  double x = 0, z = 0;   // where this display stands, m (within +-100)
  std::string topic = "candela/room";
};

// Reads [room]; `present`: the table is there, `mqtt`: so is [mqtt] (a room
// needs the broker). Calls reader.finish(). Throws ConfigError naming file,
// key and what was expected.
RoomSettings parse_room(ParamReader& reader, bool present, bool mqtt);

// One gust on TOPIC/gust, as JSON of at most kMaxMessage bytes:
//   {"v":1,"origin":"candela-a","seq":3,"t_ns":1764770000123456789,
//    "type":"gust","x":2.0,"z":0.0,"position":[0.0,0.0]}
struct RoomGust {
  static constexpr size_t kMaxMessage = 512;
  std::string origin;  // the sender's MQTT client id (1..64 printable characters)
  uint64_t seq = 0;
  int64_t t_ns = 0;  // CLOCK_REALTIME when the gust left the origin's plane S
  WindEvent::Type type = WindEvent::Type::kGust;  // kGust or kBlowOut
  double x = 0, z = 0;                            // direction * strength, m/s (|.| <= 100)
  double px = 0, pz = 0;                          // the origin's [room] position, m
};

std::string room_gust_json(const RoomGust& gust);
// Validates everything (size, JSON, each field's type and range): nullopt
// and *error says what was wrong.
std::optional<RoomGust> parse_room_gust(std::string_view payload, std::string* error);

// When and how strong `gust` reaches a display at (x, z) whose scene's wind
// is `spec` (WindField::travel).
WindTravel room_travel(const WindSpec& spec, const RoomGust& gust, double x, double z);

int64_t realtime_ns();  // CLOCK_REALTIME, the room's shared epoch (NTP on a LAN)

}  // namespace candela
