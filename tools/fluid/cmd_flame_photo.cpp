// candela-tool flame-photo: a procedurally rendered flame "photograph" for
// `candela-tool texturize`, so recipes and tests need no real footage.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <stdexcept>

#include "cli_parse.h"
#include "core/cli_usage.h"
#include "flame_photo.h"
#include "subcommand.h"

namespace {

int run_flame_photo(int argc, char** argv) {
  CLI::App app{
      "Render a procedural flame photograph (RGBA PNG with a transparent background, or\n"
      "RGB on black with --no-alpha) to use as the photo for candela-tool texturize.",
      "candela-tool flame-photo"};
  std::string out, size = "96x160";
  uint64_t seed = 1;
  bool no_alpha = false;
  app.add_option("--out,-o", out, "PNG file to write")->required();
  app.add_option("--size", size, "WIDTHxHEIGHT in pixels (16..4096)")->capture_default_str();
  app.add_option("--seed", seed, "random seed")->capture_default_str();
  app.add_flag("--no-alpha", no_alpha, "RGB flame on a black background instead of RGBA");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return candela::usage_exit(app, e);
  }
  return candela::fluid::bad_values_exit("flame-photo", [&] {
    int w = 0, h = 0;
    candela::fluid::parse_size("--size", size, w, h);
    candela::write_png(out, candela::fluid::render_flame_photo(w, h, seed, !no_alpha));
    return 0;
  });
}

}  // namespace

int candela::tool::cmd_flame_photo(int argc, char** argv) { return run_flame_photo(argc, argv); }
