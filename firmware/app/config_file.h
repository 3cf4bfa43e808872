// The kiosk's settings file, /etc/candela/candela.toml (`candela --config`):
// which scene and which display. Read like a scene (core/file_read.h: a
// regular file, at most the scene limit; nesting bounded) and validated key
// by key: errors are ConfigError "file: key: expected ...".
//   scene = "default"              # a built-in scene, or a file: "/etc/candela/my.toml"
//                                  # (with a '/' or ending in .toml; relative: to this file)
//   display = "drm"                                    # auto | drm | window | headless
//   [mqtt]                                             # optional: home automation
//   host = "192.168.1.10"                              # (input/mqtt_bridge.h, README "MQTT")
//   [room]                                             # optional: several screens, one room
//   position = [1.5, 0]                                # (input/room.h, README "Several screens")
//   [schedule]                                         # optional: app/schedule.h
#pragma once

#include <string>
#include <string_view>

#include "app/schedule.h"
#include "input/mqtt_bridge.h"

namespace candela {

struct KioskConfig {
  std::string scene;    // a built-in scene's name or a file's full path; empty: "default"
  std::string display;  // empty: not given (the command line's, or auto)
  MqttSettings mqtt;    // enabled when the file has an [mqtt] table; .room: [room]
  Schedule schedule;    // [schedule] (app/schedule.h): on/off times, fades, night, scenes
};

KioskConfig load_config_file(const std::string& path);
// The same from text already read; `path` names it in errors and is where
// relative paths start (the config fuzz target's way in).
KioskConfig load_config_text(std::string_view text, const std::string& path);

}  // namespace candela
