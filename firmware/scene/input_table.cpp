#include "scene/input_table.h"

#include <cmath>

#include "core/error.h"
#include "params/params.h"

namespace candela {

const char* input_kind_name(InputSpec::Kind kind) {
  switch (kind) {
    case InputSpec::Kind::kButton:
      return "button";
    case InputSpec::Kind::kPresence:
      return "presence";
    case InputSpec::Kind::kAnemometer:
      return "anemometer";
    case InputSpec::Kind::kBlow:
      return "blow";
    case InputSpec::Kind::kCamera:
      return "camera";
  }
  return "?";
}

namespace {

InputSpec::Kind parse_kind(ParamReader& r) {
  if (!r.has("kind"))
    r.fail("kind", "missing; expected button, presence, anemometer, blow or camera");
  const std::string k =
      r.string("kind", "", {"button", "presence", "anemometer", "blow", "camera"});
  if (k == "button") return InputSpec::Kind::kButton;
  if (k == "presence") return InputSpec::Kind::kPresence;
  if (k == "anemometer") return InputSpec::Kind::kAnemometer;
  if (k == "blow") return InputSpec::Kind::kBlow;
  return InputSpec::Kind::kCamera;
}

// `side` names where the wind comes from; the wind blows away from it.
void parse_side(ParamReader& r, InputSpec& s, const char* def) {
  const std::string side = r.string("side", def, {"left", "right", "front", "back"});
  const Fixed one = Fixed::from_int(1);
  s.dir_x = side == "left" ? one : side == "right" ? -one : Fixed{};
  s.dir_z = side == "back" ? one : side == "front" ? -one : Fixed{};
}

// Absent: the default from [wind] (gust_speed) when the wind field is known.
void read_strength(ParamReader& r, InputSpec& s, double max) {
  if (r.has("strength")) s.strength = r.fixed("strength", 0, 0, max);
}

void parse_gpio(ParamReader& r, InputSpec& s) {
  if (!r.has("chip"))
    r.fail("chip", "missing; expected a GPIO chip path, name, label or number, e.g. \"gpiochip0\"");
  s.chip = r.string("chip", "");
  if (s.chip.empty()) r.fail("chip", "expected a non-empty chip path, name, label or number");
  const bool by_offset = r.has("line"), by_name = r.has("line_name");
  if (by_offset == by_name)
    r.fail("line", "expected exactly one of line (an offset) or line_name (the line's name)");
  if (by_offset) s.line_offset = static_cast<int>(r.integer("line", 0, 0, 4095));
  if (by_name) {
    s.line_name = r.string("line_name", "");
    if (s.line_name.empty()) r.fail("line_name", "expected a non-empty line name");
  }
  const std::string bias = r.string("bias", "as-is", {"as-is", "disabled", "pull-up", "pull-down"});
  s.bias = bias == "disabled"    ? InputSpec::Bias::kDisabled
           : bias == "pull-up"   ? InputSpec::Bias::kPullUp
           : bias == "pull-down" ? InputSpec::Bias::kPullDown
                                 : InputSpec::Bias::kAsIs;
  s.active_low = r.boolean("active_low", false);
  // Reed switches bounce for a few ms; buttons ~10-20 ms; PIR modules are clean but slow.
  const int def_debounce = s.kind == InputSpec::Kind::kAnemometer ? 2
                           : s.kind == InputSpec::Kind::kPresence ? 100
                                                                  : 20;
  s.debounce_ms = static_cast<int>(r.integer("debounce_ms", def_debounce, 0, 5000));
}

}  // namespace

std::vector<InputSpec> parse_inputs(const toml::node* node, const std::string& file) {
  std::vector<InputSpec> out;
  if (!node) return out;
  const toml::array* arr = node->as_array();
  if (!arr || !arr->is_array_of_tables())
    throw ConfigError(file, "input", "expected an array of tables ([[input]])");
  for (size_t i = 0; i < arr->size(); ++i) {
    ParamReader r(arr->get(i)->as_table(), file, "input[" + std::to_string(i) + "]");
    InputSpec s;
    s.kind = parse_kind(r);
    s.name = r.string("name", std::string(input_kind_name(s.kind)) + " " + std::to_string(i));
    switch (s.kind) {
      case InputSpec::Kind::kButton:
        parse_gpio(r, s);
        parse_side(r, s, "left");
        read_strength(r, s, 30);
        break;
      case InputSpec::Kind::kPresence:
        parse_gpio(r, s);
        parse_side(r, s, "front");
        s.strength = r.fixed("strength", 0.3, 0, 30);
        break;
      case InputSpec::Kind::kBlow:
        parse_gpio(r, s);
        parse_side(r, s, "front");
        read_strength(r, s, 60);
        break;
      case InputSpec::Kind::kAnemometer:
        parse_gpio(r, s);
        parse_side(r, s, "left");
        // A common cup anemometer: 2.4 km/h per Hz = 0.667 m/s per Hz.
        s.calibration = r.number("calibration", 0.667, 1e-4, 100);
        s.window_s = r.number("window_s", 2.0, 0.2, 60);
        break;
      case InputSpec::Kind::kCamera:
        s.backend = r.string("backend", "auto", {"auto", "v4l2", "libcamera"});
        s.device = r.string("device", "auto");
        // V4L2 takes /dev/videoN; libcamera a camera id as `cam -l` lists it
        // (e.g. "/base/soc/i2c0mux/i2c@1/imx708@1a" on a Pi); auto either.
        if (s.device.empty())
          r.fail("device",
                 "expected \"auto\", a device path like /dev/video0 or a libcamera "
                 "camera id, got an empty string");
        if (s.device.rfind("video", 0) == 0)  // a V4L2 node without its /dev/
          r.fail("device",
                 "expected a device path like /dev/video0, got \"" + echo_value(s.device) + "\"");
        if (s.backend == "v4l2" && s.device != "auto" && s.device.rfind("/dev/", 0) != 0)
          r.fail("device",
                 "expected \"auto\" or a device path like /dev/video0 for backend "
                 "\"v4l2\", got \"" +
                     s.device + "\"");
        if (s.backend == "libcamera" && s.device.rfind("/dev/video", 0) == 0)
          r.fail("device",
                 "expected \"auto\" or a libcamera camera id (see `cam -l`) for "
                 "backend \"libcamera\", got the V4L2 node \"" +
                     s.device + "\"");
        s.width = static_cast<int>(r.integer("width", 160, 32, 1920));
        s.height = static_cast<int>(r.integer("height", 120, 24, 1080));
        s.fps = static_cast<int>(r.integer("fps", 15, 1, 120));
        s.mirror = r.boolean("mirror", true);
        s.sensitivity = r.number("sensitivity", 1.0, 0.01, 100);
        read_strength(r, s, 30);
        s.cooldown_ms = static_cast<int>(r.integer("cooldown_ms", 600, 0, 60000));
        break;
    }
    r.finish();
    out.push_back(std::move(s));
  }
  return out;
}

}  // namespace candela
