// candela-tool simulate: a 2-D fire simulation written as a flame clip.
#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <stdexcept>

#include "cli_parse.h"
#include "core/cli_usage.h"
#include "core/error.h"
#include "simulate_run.h"
#include "subcommand.h"

namespace {

using namespace candela::fluid;

int run_simulate(int argc, char** argv) {
  CLI::App app{
      "Simulate a 2-D flame (stable fluids: semi-Lagrangian advection, multigrid-preconditioned\n"
      "CG pressure projection, buoyancy kappa_b (T - T_amb) y, vorticity confinement eps (N x w),\n"
      "radiative cooling C_r ((T - T_amb)/(T_max - T_amb))^4) and write it as a clip folder:\n"
      "OUT/frames/frame_000000.png..., OUT/fields/field_000000.cfld... (temperature + velocity),\n"
      "OUT/manifest.toml. Units: cells, seconds, kelvin. See tools/fluid/README.md.",
      "candela-tool simulate"};
  std::string out, preset = "candle", grid, colour = "gray", name, advection,
                   render = "temperature";
  Camera camera;
  int frames = 120, substeps = 2, scale = 1;
  double fps = 30.0, warmup = 3.0, t_reference = 0.0;
  uint64_t seed = 1;
  std::vector<std::string> sources;
  std::string wind;
  bool no_fields = false, side_walls = false, open_sides = false, quiet = false;
  FluidParams base;
  app.add_option("--out,-o", out, "folder to write the clip to")->required();
  app.add_option("--frames,-n", frames, "frames to write")->capture_default_str();
  app.add_option(
         "--preset", preset,
         "starting parameters: candle (96x160) or fireplace (192x128) (coarse), fire "
         "(192x288, logs), tongues (96x256, a stretch of log, for --slices) or wick (128x256, a "
         "candle flame) (MacCormack, combustion)")
      ->capture_default_str();
  app.add_option("--grid", grid, "grid size WxH in cells (8..2048 each), e.g. 128x128");
  app.add_option("--fps", fps, "frames per second of the clip")->capture_default_str();
  app.add_option("--substeps", substeps, "solver steps per frame")->capture_default_str();
  app.add_option("--warmup", warmup, "seconds simulated before the first frame")
      ->capture_default_str();
  app.add_option("--seed", seed, "random seed (same seed, same clip)")->capture_default_str();
  auto* o_amb = app.add_option("--t-ambient", base.t_ambient, "ambient temperature, K");
  auto* o_buo = app.add_option("--buoyancy", base.buoyancy, "kappa_b, cells/s^2 per K");
  auto* o_vor = app.add_option("--vorticity", base.vorticity, "eps, vorticity confinement");
  auto* o_cool = app.add_option("--cooling", base.cooling, "C_r, K/s");
  auto* o_jit = app.add_option("--jitter", base.jitter, "per-cell randomness of heating, 0..1");
  app.add_option("--advection", advection, "semi-lagrangian or maccormack (default: the preset's)");
  auto* o_burn = app.add_option("--burn-rate", base.burn_rate, "fuel burnt per second, 1/s");
  auto* o_ign = app.add_option("--ignition", base.ignition, "fuel burns above this, K");
  auto* o_heat =
      app.add_option("--heat-release", base.heat_release, "heating per unit of fuel burnt, K");
  auto* o_flame = app.add_option("--flame-temperature", base.flame_temperature,
                                 "burning heats no cell above this, K");
  app.add_option("--source", sources,
                 "heat source (repeatable): x=,y=,rx=,ry= (fractions of the grid, y from the "
                 "bottom), angle= (deg), rate= (K/s), temp= (K), flicker= (0..1), hz=, fuel= "
                 "(per s), turb= (0..1), grain= (cells), kick= (cells/s); replaces the preset's");
  app.add_option("--wind", wind,
                 "wind speed over time, TIME:SPEED pairs (s:cells/s, + = right), linear between, "
                 "e.g. 0:0,2:30,4:0; replaces the preset's (\"none\" = still air)");
  auto* o_drag =
      app.add_option("--wind-drag", base.wind_drag, "how fast air follows the wind, 1/s");
  app.add_flag("--side-walls", side_walls, "closed left and right sides");
  app.add_flag("--open-sides", open_sides, "open left and right sides")->excludes("--side-walls");
  auto* o_tol = app.add_option("--pressure-tolerance", base.pressure_tolerance,
                               "stop the pressure solve when max|div u| <= this x max|u| / cell");
  app.add_option("--colour,--color", colour, "frame colours: gray or blackbody")
      ->capture_default_str();
  app.add_option("--render", render,
                 "temperature (gray = normalised temperature) or radiance (black-body luminance "
                 "through a camera: --exposure, soft clip from --knee)")
      ->capture_default_str();
  app.add_option("--exposure", camera.exposure,
                 "radiance: brightness of T_reference before the soft clip")
      ->capture_default_str();
  app.add_option("--knee", camera.knee, "radiance: where the soft clip starts, 0..1")
      ->capture_default_str();
  app.add_option("--soot", camera.soot,
                 "radiance: gas glows by 1 - exp(-fuel / SOOT) (soot where fuel burns); 0 = all "
                 "hot gas glows")
      ->capture_default_str();
  app.add_option("--glow", camera.glow,
                 "slices: share of a blurred copy of the light added before the soft clip (the "
                 "camera's scatter around bright flame); 0 = none")
      ->capture_default_str();
  app.add_option("--glow-radius", camera.glow_radius, "slices: the glow's Gaussian sigma, pixels")
      ->capture_default_str();
  app.add_option("--haze", camera.haze,
                 "slices: brightness (linear, 0..1) of a wide blur of the clipped picture added "
                 "after the clip (the lit air around the fire); 0 = none")
      ->capture_default_str();
  app.add_option("--haze-radius", camera.haze_radius, "slices: the haze's Gaussian sigma, pixels")
      ->capture_default_str();
  app.add_option("--scale", scale, "image pixels per cell (1..16)")->capture_default_str();
  int slices = 1;
  double slice_spacing = 0.5;
  app.add_option("--slices", slices,
                 "independent simulations side by side and in depth on one canvas (gray "
                 "radiance, --no-fields)")
      ->capture_default_str();
  bool fuel_bed = false;
  app.add_flag("--fuel-bed", fuel_bed,
               "logs and glowing coals around the flames (on the canvas of --slices)");
  bool no_back_logs = false;
  app.add_flag("--no-back-logs", no_back_logs,
               "fuel bed without its two logs behind the flames, only the front log and coals");
  app.add_option("--slice-spacing", slice_spacing, "distance between slice centres, slice widths")
      ->capture_default_str();
  double slice_flicker = 0.0;
  app.add_option("--slice-flicker", slice_flicker,
                 "slices: each slice's light flickers by this depth (0..0.5) with 1/f noise, "
                 "0.75-24 Hz")
      ->capture_default_str();
  double slice_rates = 0.0;
  app.add_option("--slice-rates", slice_rates,
                 "slices: each slice's clock runs at its own rate, spread over 1-S..1+S (0..0.6); "
                 "tongues of many sizes puff at many frequencies")
      ->capture_default_str();
  double slice_edge_fade = 0.0;
  app.add_option("--slice-edge-fade", slice_edge_fade,
                 "slices: each slice's light fades out over this share of its grid at the sides "
                 "(twice that below a top inside the canvas), 0..0.25")
      ->capture_default_str();
  double shutter = 1.0;
  app.add_option("--shutter", shutter,
                 "slices: share of each frame the shutter is open (its last substeps' light is "
                 "averaged), 0..1; 1 = the whole frame")
      ->capture_default_str();
  app.add_option(
      "--t-reference", t_reference,
      "temperature shown as full brightness, K (default: hottest cell after the warm-up)");
  app.add_option("--name", name, "clip name in the manifest (default: the folder's name)");
  app.add_flag("--no-fields", no_fields, "write only PNG frames, no .cfld fields");
  app.add_flag("--quiet,-q", quiet, "no progress on stderr");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return candela::usage_exit(app, e);
  }
  return candela::fluid::bad_values_exit("simulate", [&] {
    SimulateOptions opt;
    opt.params = preset_params(preset);
    if (!grid.empty()) parse_size("--grid", grid, opt.params.width, opt.params.height);
    if (o_amb->count()) opt.params.t_ambient = base.t_ambient;
    if (o_buo->count()) opt.params.buoyancy = base.buoyancy;
    if (o_vor->count()) opt.params.vorticity = base.vorticity;
    if (o_cool->count()) opt.params.cooling = base.cooling;
    if (o_jit->count()) opt.params.jitter = base.jitter;
    if (o_burn->count()) opt.params.burn_rate = base.burn_rate;
    if (o_ign->count()) opt.params.ignition = base.ignition;
    if (o_heat->count()) opt.params.heat_release = base.heat_release;
    if (o_flame->count()) opt.params.flame_temperature = base.flame_temperature;
    if (advection == "maccormack")
      opt.params.advection = Advection::kMacCormack;
    else if (advection == "semi-lagrangian")
      opt.params.advection = Advection::kSemiLagrangian;
    else if (!advection.empty())
      throw std::invalid_argument("--advection: semi-lagrangian or maccormack (got \"" + advection +
                                  "\")");
    if (render == "radiance")
      opt.radiance = true;
    else if (render != "temperature")
      throw std::invalid_argument("--render: temperature or radiance (got \"" + render + "\")");
    opt.camera = camera;
    if (o_drag->count()) opt.params.wind_drag = base.wind_drag;
    if (o_tol->count()) opt.params.pressure_tolerance = base.pressure_tolerance;
    if (side_walls) opt.params.boundary.open_left = opt.params.boundary.open_right = false;
    if (open_sides) opt.params.boundary.open_left = opt.params.boundary.open_right = true;
    if (!sources.empty()) {
      opt.params.sources.clear();
      for (const auto& s : sources) opt.params.sources.push_back(parse_source(s));
    }
    if (wind == "none")
      opt.params.wind.clear();
    else if (!wind.empty())
      opt.params.wind = parse_wind(wind);
    opt.params.seed = seed;
    if (colour == "gray" || colour == "grey")
      opt.colour = ColourMode::kGray;
    else if (colour == "blackbody")
      opt.colour = ColourMode::kBlackBody;
    else
      throw std::invalid_argument("--colour: gray or blackbody (got \"" + colour + "\")");
    opt.frames = frames;
    opt.fps = fps;
    opt.substeps = substeps;
    opt.warmup = warmup;
    opt.scale = scale;
    opt.slices = slices;
    opt.slice_spacing = slice_spacing;
    opt.slice_flicker = slice_flicker;
    opt.slice_rates = slice_rates;
    opt.slice_edge_fade = slice_edge_fade;
    opt.shutter = shutter;
    opt.fuel_bed = fuel_bed;
    opt.back_logs = !no_back_logs;
    opt.t_reference = t_reference;
    opt.write_fields = !no_fields;
    opt.out_dir = out;
    opt.name = name;
    opt.command = join_command(argc, argv);

    auto last = std::chrono::steady_clock::now();
    auto progress = [&](int done, int total) {
      const auto now = std::chrono::steady_clock::now();
      if (quiet || (done < total && now - last < std::chrono::milliseconds(500))) return;
      last = now;
      std::fprintf(stderr, "simulate: frame %d/%d\n", done, total);
    };
    const SimulateSummary s = run_simulation(opt, progress);
    if (!quiet)
      std::fprintf(stderr,
                   "simulate: %d frames (%d steps of %dx%d) in %.2f s -> %s (T_reference %.0f K)\n"
                   "simulate: pressure: at most %d CG iterations/step, max|div u|*cell <= %.2g x "
                   "max|u|%s\n",
                   frames, s.steps, opt.params.width, opt.params.height, s.seconds, out.c_str(),
                   s.t_reference, s.max_pressure_iterations, s.max_relative_residual,
                   s.unconverged_steps ? " (some steps hit the iteration limit)" : "");
    return 0;
  });
}

}  // namespace

int candela::tool::cmd_simulate(int argc, char** argv) { return run_simulate(argc, argv); }
