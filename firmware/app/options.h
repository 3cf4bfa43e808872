// candela's command line.
#pragma once

#include <cstdint>
#include <string>

#include "app/schedule.h"
#include "display/display.h"
#include "input/mqtt_bridge.h"

namespace candela {

struct Options {
  DisplayOptions display;
  std::string scene;   // empty: the built-in default scene
  std::string config;  // --config: the kiosk's settings file (app/config_file.h); empty: none
  bool test_pattern = false;
  bool check = false;
  bool bench = false;
  bool realtime = false;
  bool list_elements = false;
  bool mute = false;    // no sound, whatever the scene's [sound] says
  uint64_t frames = 0;  // 0: run until quit
  uint64_t seed = 0;    // 0: the scene's seed
  std::string log_level = "info";
  std::string control;  // control socket path (firmware/input/control_channel.h); empty: none
  MqttSettings mqtt;    // the --config file's [mqtt] (off without one)
  bool scene_is_name = false;   // scene is a built-in's name (the config's); else a file
  bool scene_from_cli = false;  // --scene was given (wins over the config's, also on reload)
  Schedule schedule;            // the --config file's [schedule] (absent: always on)
  // The schedule's clock: the system's, or (testing a schedule) one that
  // starts at --clock-start (local time) and runs --clock-scale times as fast.
  int64_t clock_start_ms = -1;  // -1: the system's clock
  double clock_scale = 1.0;
};

// Parses argv. Returns -1 to go on, or an exit status (after --help, or a
// usage error, which is printed).
int parse_options(int argc, char** argv, Options& out);

}  // namespace candela
