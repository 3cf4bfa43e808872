#include "app/options.h"

#include <time.h>

#include <CLI/CLI.hpp>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <string>

#include "app/config_file.h"
#include "app/kiosk.h"
#include "core/cli_usage.h"
#include "core/error.h"
#include "core/wxh.h"
#include "display/frame_writer.h"
#include "input/gpio_line.h"

namespace candela {
namespace {

// Plain decimal digits only, at most `max`: "-1", "1e11", "0x10", "12abc" and
// anything that would overflow are refused (strtoull and CLI11 take some of them).
bool parse_count(const std::string& s, uint64_t max, uint64_t* out) {
  if (s.empty() || s.size() > 20) return false;
  uint64_t v = 0;
  for (char c : s) {
    if (c < '0' || c > '9') return false;
    const uint64_t d = static_cast<uint64_t>(c - '0');
    if (v > (max - d) / 10) return false;
    v = v * 10 + d;
  }
  *out = v;
  return true;
}

int usage_error(const char* option, const std::string& expected, const std::string& got) {
  const std::string shown = got.size() > 40 ? got.substr(0, 40) + "..." : got;
  std::fprintf(stderr, "candela: %s: expected %s, got '%s'\n", option, expected.c_str(),
               shown.c_str());
  return 2;
}

}  // namespace

int parse_options(int argc, char** argv, Options& o) {
  CLI::App app{
      "candela: a living candle or fireplace for a screen.\n"
      "With no options it shows the built-in scene on the best display it finds\n"
      "(DRM/KMS, then a desktop window, then headless).",
      "candela"};
  // Also names the GPIO library: which libgpiod API this build was made for.
  app.set_version_flag("--version", "candela 0.1.0\n" + gpio_library_version());
  std::string size, frames, seed;
  // Not CLI::ExistingFile: the scene reader says what is wrong with the path
  // ("too many levels of symbolic links", "not a regular file (a FIFO)").
  app.add_option("--scene", o.scene, "Scene file (TOML); default: the built-in scene");
  app.add_option("--config", o.config,
                 "Kiosk settings (TOML: scene, display, [mqtt]), e.g. /etc/candela/candela.toml; "
                 "--scene, --test-pattern and --display on the command line win");
  app.add_flag("--test-pattern", o.test_pattern,
               "Show colour bars, a frame counter and a moving marker");
  app.add_flag("--check", o.check,
               "Validate the scene and everything it references, then exit (0 = valid)");
  app.add_option("--display", o.display.kind, "Where to draw: auto, drm, window or headless")
      ->check(CLI::IsMember({"auto", "drm", "window", "headless"}));
  app.add_option("--drm-device", o.display.drm_device, "DRM card to use, e.g. /dev/dri/card1");
  app.add_option("--size", size, "Size WxH (headless, window; DRM: the mode to pick)");
  app.add_option("--refresh", o.display.refresh_hz, "DRM: refresh rate of the mode to pick (Hz)")
      ->check(CLI::Range(1, 1000));
  app.add_option("--frames", frames, "Stop after N frames (default: run until quit)");
  app.add_option("--out", o.display.out_path,
                 "Headless: write frames to a PNG folder, a .y4m file or an .mp4 (needs ffmpeg); "
                 "with --display auto this picks headless");
  app.add_option("--fps", o.display.fps,
                 "Frame rate of written video; headless animation advances 1/fps per frame")
      ->check(CLI::Range(1, 240));
  app.add_option("--seed", seed, "Random seed, 1 to 2^63-1 (default: the scene's)");
  app.add_flag(
      "--realtime", o.realtime,
      "Headless: hold --fps by the wall clock and animate in real time, like a screen "
      "(default: as fast as possible, one step per frame); without --out a scene's [sound] "
      "plays through ALSA");
  app.add_flag("--mute", o.mute,
               "No sound, whatever the scene's [sound] says (no ALSA device, no .wav)");
  app.add_flag("--bench", o.bench, "Print frame-time statistics as one JSON line after the run");
  app.add_flag("--list-elements", o.list_elements, "List the kinds of scene element and exit");
  app.add_option("--log-level", o.log_level, "debug, info, warn or error")
      ->check(CLI::IsMember({"debug", "info", "warn", "error"}));
  app.add_option("--control", o.control,
                 "Listen for wind commands and state queries on this UNIX socket (mode 0600); "
                 "see README");
  std::string clock_start;
  app.add_option("--clock-start", clock_start,
                 "Testing a [schedule]: the kiosk's clock starts at this local time, "
                 "YYYY-MM-DDTHH:MM[:SS] (default: the system's clock)");
  app.add_option("--clock-scale", o.clock_scale,
                 "Testing a [schedule]: the kiosk's clock runs this many times as fast "
                 "(1 to 100000; with --clock-start)")
      ->check(CLI::Range(1.0, 100000.0));
  bool no_vsync = false;
  app.add_flag("--no-vsync", no_vsync, "Do not wait for vertical blank (window)");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return candela::usage_exit(app, e);
  }
  o.display.vsync = !no_vsync;
  o.scene_from_cli = !o.scene.empty();
  if (!clock_start.empty()) {
    struct tm tm {};
    const char* end = strptime(clock_start.c_str(), "%Y-%m-%dT%H:%M", &tm);
    if (end && *end == ':') end = strptime(end, ":%S", &tm);
    if (!end || *end)
      return usage_error("--clock-start", "a local time YYYY-MM-DDTHH:MM[:SS]", clock_start);
    tm.tm_isdst = -1;
    // mktime normalises: February 30th would be March 2nd. A date that does
    // not exist is refused, not moved (issue 34).
    const struct tm asked = tm;
    const time_t t = mktime(&tm);
    if (t == static_cast<time_t>(-1) || tm.tm_mday != asked.tm_mday || tm.tm_mon != asked.tm_mon ||
        tm.tm_year != asked.tm_year)
      return usage_error("--clock-start", "a date that exists, YYYY-MM-DDTHH:MM[:SS]", clock_start);
    o.clock_start_ms = static_cast<int64_t>(t) * 1000;
  } else if (app.count("--clock-scale")) {
    std::fprintf(stderr, "candela: --clock-scale needs --clock-start\n");
    return 2;
  }
  if (!o.config.empty()) {
    KioskConfig c;
    try {
      c = load_config_file(o.config);
    } catch (const ConfigError& e) {
      std::fprintf(stderr, "candela: %s\n", e.what());
      return 2;
    }
    if (o.scene.empty() && !o.test_pattern) {
      o.scene = c.scene;
      o.scene_is_name = is_scene_name(c.scene);  // the config's "default": a built-in
    }
    if (!c.display.empty() && app.count("--display") == 0) o.display.kind = c.display;
    o.mqtt = std::move(c.mqtt);
    o.schedule = std::move(c.schedule);
  }
  if (!size.empty()) {
    const std::optional<WxH> s = parse_wxh(size, {16, 16}, {16384, 16384});
    if (!s) return usage_error("--size", "WxH, each 16 to 16384, e.g. 1280x720", size);
    o.display.width = s->width;
    o.display.height = s->height;
  }
  // Up to 2^53 frames: centuries at 60 Hz, and exact as a double in statistics.
  if (!frames.empty() && !parse_count(frames, uint64_t{1} << 53, &o.frames))
    return usage_error("--frames", "a whole number of frames, 0 to 2^53 (0: run until quit)",
                       frames);
  // The scene's `seed` takes the same range; 0 would mean "the scene's".
  if (!seed.empty() && (!parse_count(seed, INT64_MAX, &o.seed) || o.seed == 0))
    return usage_error("--seed", "a whole number from 1 to 2^63-1", seed);
  if (!o.display.out_path.empty()) {
    if (const std::string why = frame_sink_problem(o.display.out_path); !why.empty())
      return usage_error("--out", why, o.display.out_path);
  }
  if (!o.display.out_path.empty() && o.display.kind == "auto") o.display.kind = "headless";
  if (!o.display.out_path.empty() && o.display.kind != "headless") {
    std::fprintf(stderr, "candela: --out needs --display headless\n");
    return 2;
  }
  return -1;
}

}  // namespace candela
