#include "app/options.h"

#include <CLI/CLI.hpp>
#include <cstdio>

#include "input/gpio_line.h"

namespace candela {

int parse_options(int argc, char** argv, Options& o) {
  CLI::App app{
      "candela: a living candle or fireplace for a screen.\n"
      "With no options it shows the built-in scene on the best display it finds\n"
      "(DRM/KMS, then a desktop window, then headless).",
      "candela"};
  // Also names the GPIO library: which libgpiod API this build was made for.
  app.set_version_flag("--version", "candela 0.1.0\n" + gpio_library_version());
  std::string size;
  app.add_option("--scene", o.scene, "Scene file (TOML); default: the built-in scene")
      ->check(CLI::ExistingFile);
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
  app.add_option("--frames", o.frames, "Stop after N frames (default: run until quit)");
  app.add_option("--out", o.display.out_path,
                 "Headless: write frames to a PNG folder, a .y4m file or an .mp4 (needs ffmpeg); "
                 "with --display auto this picks headless");
  app.add_option("--fps", o.display.fps,
                 "Frame rate of written video; headless animation advances 1/fps per frame")
      ->check(CLI::Range(1, 240));
  app.add_option("--seed", o.seed, "Random seed (default: the scene's)");
  app.add_flag("--realtime", o.realtime,
               "Headless: hold --fps by the wall clock and animate in real time, like a screen "
               "(default: as fast as possible, one step per frame)");
  app.add_flag("--bench", o.bench, "Print frame-time statistics as one JSON line after the run");
  app.add_flag("--list-elements", o.list_elements, "List the kinds of scene element and exit");
  app.add_option("--log-level", o.log_level, "debug, info, warn or error")
      ->check(CLI::IsMember({"debug", "info", "warn", "error"}));
  app.add_option("--control", o.control,
                 "Listen for wind commands and state queries on this UNIX socket (mode 0600); "
                 "see README");
  bool no_vsync = false;
  app.add_flag("--no-vsync", no_vsync, "Do not wait for vertical blank (window)");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  o.display.vsync = !no_vsync;
  if (!size.empty()) {
    int w = 0, h = 0;
    char extra = 0;
    if (std::sscanf(size.c_str(), "%dx%d%c", &w, &h, &extra) != 2 || w < 16 || h < 16 ||
        w > 16384 || h > 16384) {
      std::fprintf(stderr, "candela: --size: expected WxH, e.g. 1280x720, got '%s'\n",
                   size.c_str());
      return 2;
    }
    o.display.width = w;
    o.display.height = h;
  }
  if (!o.display.out_path.empty() && o.display.kind == "auto") o.display.kind = "headless";
  if (!o.display.out_path.empty() && o.display.kind != "headless") {
    std::fprintf(stderr, "candela: --out needs --display headless\n");
    return 2;
  }
  return -1;
}

}  // namespace candela
