// What the scene says about the room's inputs: [[input]] tables, each a GPIO
// sensor (button, presence, anemometer, blow) or a camera. Parsed and
// validated with the scene, so `candela --check` reports their mistakes too.
// Here in scene/, not input/: the scene names its inputs without including
// the code that runs them (input/ reads these specs).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/fixed.h"

namespace candela {

struct InputSpec {
  enum class Kind : uint8_t { kButton, kPresence, kAnemometer, kBlow, kCamera };
  enum class Bias : uint8_t { kAsIs, kDisabled, kPullUp, kPullDown };

  Kind kind = Kind::kButton;
  std::string name;

  // GPIO: chip by path (/dev/gpiochip0), name (gpiochip0), label (pinctrl-bcm2711)
  // or number; line by offset or by name (exactly one of them).
  std::string chip;
  int line_offset = -1;
  std::string line_name;
  Bias bias = Bias::kAsIs;
  bool active_low = false;
  int debounce_ms = 0;

  // Where the wind comes from (unit vector of where it blows to, x right, z toward viewer).
  Fixed dir_x, dir_z;
  // Peak gust (button, blow, camera) or draught (presence) in m/s; < 0: the default.
  Fixed strength = Fixed::from_int(-1);
  // Anemometer: m/s per pulse per second, and the window the rate is measured over.
  double calibration = 0.667;
  double window_s = 2.0;

  // Camera.
  std::string device = "auto";   // "auto" (first capture device) or /dev/videoN
  std::string backend = "auto";  // auto | v4l2 | libcamera
  int width = 160, height = 120, fps = 15;
  bool mirror = true;        // a camera facing the room sees left and right swapped
  double sensitivity = 1.0;  // scales motion into wind
  int cooldown_ms = 600;     // the least time between two camera gusts

  bool is_gpio() const { return kind != Kind::kCamera; }
};

const char* input_kind_name(InputSpec::Kind kind);

}  // namespace candela
