// candela-studio MODEL [STORY], run as `candela-tool studio MODEL [STORY]`:
// the flame studio (tools/studio/README.md).
#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <optional>

#include "core/cli_usage.h"
#include "core/wxh.h"
#include "studio.h"

namespace {

int run(int argc, char** argv) {
  CLI::App app{
      "The flame studio: play a model (or a story) through the runtime's renderer, edit its "
      "weights and colour, watch the clips' tracks through PCA space, save a scene",
      "candela-tool studio"};
  candela::studio::StudioOptions o;
  std::string size;
  bool no_vsync = false;
  app.add_option("MODEL", o.model, "model file (.cmodel) or builtin:fire / builtin:candle")
      ->required();
  app.add_option("STORY", o.story, "a story file or builtin:NAME, played instead of the clips");
  app.add_option("--size", size, "window size WxH (default 1280x720)");
  app.add_option("--script", o.script, "scripted input, one command a line (tests)");
  app.add_option("--bench", o.bench_frames,
                 "run N frames unpaced with the UI and 3-D view visible, then print frame "
                 "times as one JSON line")
      ->check(CLI::Range(1, 1000000));
  app.add_flag("--no-vsync", no_vsync, "do not wait for the display's refresh");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return candela::usage_exit(app, e);
  }
  if (!size.empty()) {
    const std::optional<candela::WxH> s = candela::parse_wxh(size, {200, 150}, {8192, 8192});
    if (!s) {
      std::fprintf(stderr,
                   "candela-tool studio: --size: expected WxH (200x150 to 8192x8192), got '%s'\n",
                   size.c_str());
      return 2;
    }
    o.width = s->width;
    o.height = s->height;
  }
  o.vsync = !no_vsync;
  return candela::studio::run_studio(o);
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "candela-tool studio: %s\n", e.what());
    return 1;
  }
}
