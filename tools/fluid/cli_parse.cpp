#include "cli_parse.h"

#include <cmath>
#include <cstdlib>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "core/wxh.h"

namespace candela::fluid {
namespace {

double to_number(const std::string& option, const std::string& s) {
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  if (s.empty() || end != s.c_str() + s.size() || !std::isfinite(v))
    throw std::invalid_argument(option + ": expected a number, got \"" + s + "\"");
  return v;
}

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::string cur;
  std::istringstream in(s);
  while (std::getline(in, cur, sep)) out.push_back(cur);
  return out;
}

}  // namespace

void parse_size(const std::string& option, const std::string& text, int& w, int& h) {
  const std::optional<WxH> s = parse_wxh(text, {1, 1}, {65536, 65536});
  if (!s)
    throw std::invalid_argument(option + ": expected WIDTHxHEIGHT (e.g. 128x128), got \"" + text +
                                "\"");
  w = s->width;
  h = s->height;
}

HeatSource parse_source(const std::string& text) {
  HeatSource s;
  for (const std::string& item : split(text, ',')) {
    const auto eq = item.find('=');
    if (eq == std::string::npos)
      throw std::invalid_argument("--source: expected KEY=VALUE items separated by commas, got \"" +
                                  item + "\"");
    const std::string key = item.substr(0, eq), val = item.substr(eq + 1);
    const double v = to_number("--source " + key, val);
    if (key == "x")
      s.x = v;
    else if (key == "y")
      s.y = v;
    else if (key == "rx")
      s.rx = v;
    else if (key == "ry")
      s.ry = v;
    else if (key == "r")
      s.rx = s.ry = v;
    else if (key == "rate")
      s.rate = v;
    else if (key == "temp")
      s.temperature = v;
    else if (key == "flicker")
      s.flicker = v;
    else if (key == "hz")
      s.flicker_hz = v;
    else if (key == "angle")
      s.angle = v;
    else if (key == "fuel")
      s.fuel = v;
    else if (key == "turb")
      s.turbulence = v;
    else if (key == "grain")
      s.grain = v;
    else if (key == "kick")
      s.kick = v;
    else
      throw std::invalid_argument(
          "--source: unknown key \"" + key +
          "\" (expected x, y, r, rx, ry, rate, temp, flicker, hz, angle, fuel, turb, grain, kick)");
  }
  return s;
}

std::vector<WindKey> parse_wind(const std::string& text) {
  std::vector<WindKey> keys;
  for (const std::string& item : split(text, ',')) {
    const auto colon = item.find(':');
    if (colon == std::string::npos)
      throw std::invalid_argument("--wind: expected TIME:SPEED pairs separated by commas, got \"" +
                                  item + "\"");
    keys.push_back({to_number("--wind time", item.substr(0, colon)),
                    to_number("--wind speed", item.substr(colon + 1))});
    if (keys.size() > 1 && !(keys.back().time > keys[keys.size() - 2].time))
      throw std::invalid_argument("--wind: times must increase strictly");
  }
  if (keys.empty()) throw std::invalid_argument("--wind: at least one TIME:SPEED pair");
  return keys;
}

std::string join_command(int argc, char** argv) {
  std::string s;
  for (int k = 0; k < argc; ++k) {
    if (k) s += ' ';
    const std::string a = argv[k];
    if (a.find_first_of(" \t\"'") == std::string::npos && !a.empty()) {
      s += a;
    } else {
      s += '\'';
      for (char c : a) s += c == '\'' ? std::string("'\\''") : std::string(1, c);
      s += '\'';
    }
  }
  return s;
}

}  // namespace candela::fluid
