// candela-tool texturize: a simulated clip + one photo of fire -> a fire
// animation with the photo's detail (Kogawa, Dobashi, Yamamoto).
#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "cli_parse.h"
#include "core/cli_usage.h"
#include "core/error.h"
#include "fire_animation.h"
#include "sim_dataset.h"
#include "subcommand.h"

namespace {

using namespace candela::fluid;

int run_texturize(int argc, char** argv) {
  CLI::App app{
      "Synthesise a fire animation from a simulated clip (candela-tool simulate output, with\n"
      "fields) and one photo of fire. Ashikhmin texture synthesis with user control: upper\n"
      "L-neighbourhood compares colours (output vs photo), lower L compares the simulated\n"
      "temperature with the photo's alpha (or luminance); SSD; white-noise start, raster order.\n"
      "Search: Ashikhmin's coherent candidates plus --random-candidates random photo pixels.\n"
      "Only key frames are synthesised; between them the image is advected (back-traced) with\n"
      "the simulation's velocity, and m frames cross-dissolve into each next key frame.\n"
      "Writes OUT/frames/frame_000000.png... (RGB) + OUT/manifest.toml.",
      "candela-tool texturize"};
  std::string photo_path, sim, out, control = "auto", name;
  AnimateParams p;
  int frames = 0;
  bool quiet = false;
  app.add_option("--photo", photo_path, "photo of fire (PNG; RGBA, or RGB on a dark background)")
      ->required();
  app.add_option("--sim", sim, "clip folder written by candela-tool simulate (needs its fields)")
      ->required();
  app.add_option("--out,-o", out, "folder to write the animation to")->required();
  app.add_option("--scale", p.scale, "output pixels per simulation cell")->capture_default_str();
  app.add_option("--key-interval,-k", p.key_interval, "K: frames between key frames")
      ->capture_default_str();
  app.add_option("--dissolve,-m", p.dissolve, "m: frames cross-dissolved into each key frame")
      ->capture_default_str();
  app.add_option("--neighbourhood", p.synth.neighbourhood, "L-shape size n (odd, n x n)")
      ->capture_default_str();
  app.add_option("--random-candidates", p.synth.random_candidates,
                 "random photo pixels tried per output pixel besides the coherent ones")
      ->capture_default_str();
  app.add_option("--control-weight", p.synth.control_weight,
                 "weight of the temperature (lower L) term against colour")
      ->capture_default_str();
  app.add_option("--passes", p.synth.passes, "raster passes per key frame")->capture_default_str();
  app.add_option("--control", control,
                 "photo channel matched to temperature: auto, alpha, luminance")
      ->capture_default_str();
  app.add_option("--frames,-n", frames, "frames to make (default: all of the clip)");
  app.add_flag("--independent", p.independent,
               "synthesise every frame on its own (no advection; for comparison)");
  app.add_option("--seed", p.seed, "random seed")->capture_default_str();
  app.add_option("--name", name, "clip name in the manifest (default: the folder's name)");
  app.add_flag("--quiet,-q", quiet, "no progress on stderr");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return candela::usage_exit(app, e);
  }
  return candela::fluid::bad_values_exit("texturize", [&] {
    validate(p);
    ControlChannel channel;
    if (control == "auto")
      channel = ControlChannel::kAuto;
    else if (control == "alpha")
      channel = ControlChannel::kAlpha;
    else if (control == "luminance")
      channel = ControlChannel::kLuminance;
    else
      throw std::invalid_argument("--control: auto, alpha or luminance (got \"" + control + "\")");
    const SimManifest sm = read_manifest(sim);
    if (!sm.has_fields)
      throw candela::ConfigError(manifest_path(sim), "fields",
                                 "a [fields] table: simulate the clip without --no-fields");
    if (frames == 0) frames = sm.frames;
    if (frames < 0 || frames > sm.frames)
      throw std::invalid_argument("--frames: 1.." + std::to_string(sm.frames) +
                                  " (the clip's length)");
    const Exemplar photo =
        make_exemplar(candela::read_png(photo_path), channel, p.synth.neighbourhood);
    namespace fs = std::filesystem;
    std::error_code ec;
    fs::create_directories(fs::path(out) / "frames", ec);
    if (ec) throw candela::RuntimeError("cannot create " + out + ": " + ec.message());

    const auto start = std::chrono::steady_clock::now();
    auto last = start;
    int width = 0, height = 0;
    auto fields = [&](int f) {
      FieldFrame ff = read_field_file(field_path(sim, f));
      if (ff.temperature.width != sm.grid_width || ff.temperature.height != sm.grid_height)
        throw candela::ConfigError(field_path(sim, f), "width/height",
                                   "the size the manifest gives, " + std::to_string(sm.grid_width) +
                                       "x" + std::to_string(sm.grid_height));
      return ff;
    };
    auto sink = [&](int f, const RgbImage& img) {
      width = img.width;
      height = img.height;
      candela::write_png(frame_path(out, f), to_image(img));
      const auto now = std::chrono::steady_clock::now();
      if (!quiet && (now - last > std::chrono::milliseconds(500) || f + 1 == frames)) {
        last = now;
        std::fprintf(stderr, "texturize: frame %d/%d\n", f + 1, frames);
      }
    };
    const AnimateStats st = animate_fire(photo, p, frames, sm.fps, fields, sink);

    SimManifest m;
    m.name = name;
    if (m.name.empty()) {
      fs::path d = fs::absolute(out).lexically_normal();
      if (d.filename().empty()) d = d.parent_path();
      m.name = d.filename().string();
    }
    m.source = "candela-tool texturize";
    m.command = join_command(argc, argv);
    m.frames = frames;
    m.fps = sm.fps;
    m.width = width;
    m.height = height;
    m.colour = "rgb";
    write_manifest(out, m);
    if (!quiet)
      std::fprintf(stderr, "texturize: %d frames (%d key frames) in %.2f s -> %s\n", frames,
                   st.key_frames,
                   std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
                   out.c_str());
    return 0;
  });
}

}  // namespace

int candela::tool::cmd_texturize(int argc, char** argv) { return run_texturize(argc, argv); }
