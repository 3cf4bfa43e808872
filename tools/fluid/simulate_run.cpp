#include "simulate_run.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <stdexcept>

#include "core/error.h"
#include "core/random.h"
#include "field_file.h"
#include "fuel_bed.h"
#include "lattice_noise.h"
#include "sim_dataset.h"

namespace candela::fluid {

FluidParams preset_params(const std::string& name) {
  FluidParams p;
  if (name == "candle") {
    p.width = 96;
    p.height = 160;
    p.buoyancy = 0.08;
    p.vorticity = 0.8;
    p.cooling = 6000.0;
    p.jitter = 0.5;
    HeatSource s;
    s.x = 0.5;
    s.y = 0.1;
    s.rx = 0.07;
    s.ry = 0.1;
    s.rate = 40000.0;
    s.flicker = 0.4;
    s.flicker_hz = 5.0;
    p.sources = {s};
    // An occasional breeze from the left and back, so the clip has both calm
    // and leaning flames.
    p.wind = {{0.0, 0.0}, {6.0, 0.0}, {7.0, 25.0}, {8.5, 25.0}, {9.5, 0.0}};
    p.wind_drag = 1.5;
  } else if (name == "fireplace") {
    p.width = 192;
    p.height = 128;
    p.buoyancy = 0.1;
    p.vorticity = 2.5;
    p.cooling = 8000.0;
    p.jitter = 0.8;
    // A row of logs: several sources, each with its own flicker.
    for (double x : {0.3, 0.4, 0.5, 0.6, 0.7}) {
      HeatSource s;
      s.x = x;
      s.y = 0.08;
      s.rx = 0.06;
      s.ry = 0.08;
      s.rate = 40000.0;
      s.flicker = 0.6;
      s.flicker_hz = 4.0;
      p.sources.push_back(s);
    }
  } else if (name == "fire") {
    // Logs on a grate: a long log across the front, two shorter ones leaning
    // on it; each feeds fuel and upward jets through a moving noise, so
    // tongues rise from separate places, merge, split and detach.
    p.width = 192;
    p.height = 288;
    p.advection = Advection::kMacCormack;
    p.buoyancy = 0.75;
    p.vorticity = 4.5;
    p.cooling = 4000.0;
    p.mixing = 6.0;
    p.jitter = 0.0;
    p.burn_rate = 10.0;
    p.ignition = 650.0;
    p.heat_release = 500.0;
    // Still air that damps sideways drift: a 2-D plume otherwise sways as a
    // whole (a 3-D fire's sides entrain air and hold it upright).
    p.wind = {{0.0, 0.0}};
    p.wind_drag = 6.0;
    struct Log {
      double x, y, rx, ry, angle;
    };
    for (const Log& l : {Log{0.5, 0.06, 0.42, 0.03, 0.0}, Log{0.33, 0.1, 0.22, 0.028, 10.0},
                         Log{0.67, 0.11, 0.22, 0.028, -8.0}}) {
      HeatSource s;
      s.x = l.x;
      s.y = l.y;
      s.rx = l.rx;
      s.ry = l.ry;
      s.angle = l.angle;
      s.rate = 7000.0;
      s.temperature = 1300.0;
      s.fuel = 250.0;
      s.turbulence = 0.9;
      s.grain = 4.5;
      s.kick = 450.0;
      s.flicker = 0.5;
      s.flicker_hz = 8.0;
      p.sources.push_back(s);
    }
  } else if (name == "tongues") {
    // A short stretch of burning log: a few tongues, for --slices (several
    // of them side by side make a hearth's fire). Narrow, so neighbouring
    // tongues cannot merge into the one sheet a wide 2-D plume becomes;
    // fast (real fire decorrelates in 25-40 ms) and fed in broad patches.
    p = preset_params("fire");
    p.width = 96;
    p.height = 256;
    p.buoyancy = 1.3;
    HeatSource s = p.sources.front();
    s.x = 0.5;
    s.y = 0.05;
    s.rx = 0.38;
    s.ry = 0.04;
    s.angle = 0.0;
    s.rate = 9000.0;
    s.fuel = 600.0;
    s.turbulence = 0.7;
    s.grain = 9.0;
    s.kick = 450.0;
    s.flicker_hz = 22.0;
    p.sources = {s};
  } else if (name == "wick") {
    // A candle flame: fuel vapour from a small wick, burning in still air.
    p.width = 128;
    p.height = 256;
    p.advection = Advection::kMacCormack;
    p.buoyancy = 0.4;
    p.vorticity = 3.0;
    p.cooling = 7000.0;
    p.mixing = 5.0;
    p.jitter = 0.0;
    p.burn_rate = 6.0;
    p.ignition = 650.0;
    p.heat_release = 500.0;
    p.wind = {{0.0, 0.0}};
    p.wind_drag = 3.0;
    HeatSource s;
    s.x = 0.5;
    s.y = 0.1;
    s.rx = 0.14;
    s.ry = 0.06;
    s.rate = 8000.0;
    s.temperature = 1400.0;
    s.fuel = 300.0;
    s.turbulence = 0.6;
    s.grain = 4.0;
    s.kick = 60.0;
    s.flicker = 0.5;
    s.flicker_hz = 6.0;
    p.sources = {s};
  } else {
    throw std::invalid_argument(
        "preset: \"candle\", \"fireplace\", \"fire\", \"tongues\" or \"wick\" (got \"" + name +
        "\")");
  }
  return p;
}

SimulateSummary run_simulation(const SimulateOptions& opt, const Progress& progress) {
  FluidParams params = opt.params;
  if (params.sources.empty()) params.sources.push_back(HeatSource{});
  validate(params);
  if (opt.frames < 1 || opt.frames > 1000000) throw std::invalid_argument("frames: 1..1000000");
  if (!(opt.fps > 0.0) || opt.fps > 1000.0) throw std::invalid_argument("fps: a rate in (0, 1000]");
  if (opt.substeps < 1 || opt.substeps > 100) throw std::invalid_argument("substeps: 1..100");
  if (!(opt.warmup >= 0.0) || opt.warmup > 3600.0)
    throw std::invalid_argument("warmup: 0..3600 seconds");
  if (opt.scale < 1 || opt.scale > 16) throw std::invalid_argument("scale: 1..16");
  if (!(opt.camera.exposure > 0.0) || !std::isfinite(opt.camera.exposure) ||
      opt.camera.exposure > 1e6)
    throw std::invalid_argument("exposure: a number in (0, 1e6]");
  if (!(opt.camera.soot >= 0.0) || !std::isfinite(opt.camera.soot))
    throw std::invalid_argument("soot: fuel units >= 0");
  if (!(opt.camera.glow >= 0.0) || !(opt.camera.glow <= 10.0))
    throw std::invalid_argument("glow: a number in 0..10");
  if (!(opt.camera.glow_radius >= 0.5) || !(opt.camera.glow_radius <= 64.0))
    throw std::invalid_argument("glow-radius: pixels in 0.5..64");
  if (!(opt.camera.haze >= 0.0) || !(opt.camera.haze <= 1.0))
    throw std::invalid_argument("haze: a brightness in 0..1");
  if (!(opt.camera.haze_radius >= 0.5) || !(opt.camera.haze_radius <= 64.0))
    throw std::invalid_argument("haze-radius: pixels in 0.5..64");
  if ((opt.camera.glow > 0.0 || opt.camera.haze > 0.0) && opt.slices < 2)
    throw std::invalid_argument("glow, haze: apply to the canvas of --slices 2 or more");
  if (!(opt.camera.knee >= 0.0) || !(opt.camera.knee < 1.0))
    throw std::invalid_argument("knee: a number in [0, 1)");
  if (opt.slices < 1 || opt.slices > 64) throw std::invalid_argument("slices: 1..64");
  if (!(opt.slice_spacing > 0.0) || opt.slice_spacing > 4.0)
    throw std::invalid_argument("slice-spacing: a number in (0, 4] (slice widths)");
  if (opt.slices > 1 && (!opt.radiance || opt.colour != ColourMode::kGray))
    throw std::invalid_argument("slices: need --render radiance and --colour gray");
  if (!(opt.slice_flicker >= 0.0) || !(opt.slice_flicker <= 0.5))
    throw std::invalid_argument("slice-flicker: a depth in 0..0.5");
  if (opt.slice_flicker > 0.0 && opt.slices < 2)
    throw std::invalid_argument("slice-flicker: applies to --slices 2 or more");
  if (!(opt.slice_rates >= 0.0) || !(opt.slice_rates <= 0.6))
    throw std::invalid_argument("slice-rates: a spread in 0..0.6");
  if (opt.slice_rates > 0.0 && opt.slices < 2)
    throw std::invalid_argument("slice-rates: applies to --slices 2 or more");
  if (!(opt.slice_edge_fade >= 0.0) || !(opt.slice_edge_fade <= 0.25))
    throw std::invalid_argument("slice-edge-fade: a share of the grid in 0..0.25");
  if (!(opt.shutter > 0.0) || !(opt.shutter <= 1.0))
    throw std::invalid_argument("shutter: a share of the frame in (0, 1]");
  if (opt.fuel_bed && opt.slices < 2)
    throw std::invalid_argument("fuel-bed: drawn on the canvas of --slices 2 or more");
  if (!opt.back_logs && !opt.fuel_bed)
    throw std::invalid_argument("no-back-logs: a choice about the fuel bed; add --fuel-bed");
  if (opt.slices > 1 && opt.write_fields)
    throw std::invalid_argument("slices: fields are per simulation; use --no-fields");
  if (opt.out_dir.empty()) throw std::invalid_argument("out: a folder to write the clip to");
  double t_ref = opt.t_reference;
  if (t_ref != 0.0 && (!(t_ref > params.t_ambient) || !std::isfinite(t_ref)))
    throw std::invalid_argument("t-reference: a temperature above the ambient temperature");

  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(fs::path(opt.out_dir) / "frames", ec);
  if (!ec && opt.write_fields) fs::create_directories(fs::path(opt.out_dir) / "fields", ec);
  if (ec) throw RuntimeError("cannot create " + opt.out_dir + ": " + ec.message());

  const auto start = std::chrono::steady_clock::now();
  // One solver per slice, each with its own seed.
  std::vector<FluidSolver> solvers;
  solvers.reserve(opt.slices);
  for (int k = 0; k < opt.slices; ++k) {
    FluidParams p = params;
    p.seed = params.seed + 0x9e3779b9ull * static_cast<uint64_t>(k);
    solvers.emplace_back(p);
  }
  // Each slice's clock rate: evenly spread, in a seeded order (the
  // placement below decides depth, so rate and size are independent).
  std::vector<double> rate(opt.slices, 1.0);
  if (opt.slices > 1 && opt.slice_rates > 0.0) {
    Pcg32 rng(params.seed * 0x9e3779b1ull + 5);
    for (int k = 0; k < opt.slices; ++k)
      rate[k] = 1.0 - opt.slice_rates + 2.0 * opt.slice_rates * k / (opt.slices - 1);
    for (int k = opt.slices - 1; k > 0; --k)
      std::swap(rate[k], rate[rng.next_u32() % static_cast<uint32_t>(k + 1)]);
  }
  SimulateSummary sum;
  const double dt = 1.0 / (opt.fps * opt.substeps);
  auto one_step = [&] {
    for (size_t k = 0; k < solvers.size(); ++k) {
      FluidSolver& solver = solvers[k];
      const StepStats st = solver.step(dt * rate[k]);
      ++sum.steps;
      sum.max_pressure_iterations = std::max(sum.max_pressure_iterations, st.pressure.iterations);
      if (!st.pressure.converged) ++sum.unconverged_steps;
      if (st.max_speed > 0.0)
        sum.max_relative_residual =
            std::max(sum.max_relative_residual, st.pressure.residual / st.max_speed);
    }
  };
  const int warm_steps = static_cast<int>(std::lround(opt.warmup / dt));
  for (int k = 0; k < warm_steps; ++k) one_step();
  // Automatic reference: the flame's core after the warm-up (sources rarely
  // reach their own temperature once the flow carries heat away), so frames
  // use the whole gray range.
  if (t_ref == 0.0) {
    for (const FluidSolver& solver : solvers) t_ref = std::max(t_ref, solver.max_temperature());
    if (t_ref < params.t_ambient + 1.0)
      for (const HeatSource& s : params.sources) t_ref = std::max(t_ref, s.temperature);
  }

  // Where each slice lands: centres spread evenly across the canvas with a
  // seeded jitter; slices farther back are smaller, dimmer and stand a
  // little higher (the fire bed seen from above), as in a real hearth.
  const int canvas_h = params.height * opt.scale;
  const int canvas_w = static_cast<int>(
      std::lround(params.width * opt.scale * (1.0 + (opt.slices - 1) * opt.slice_spacing)));
  std::vector<SlicePlacement> placement(opt.slices);
  {
    Pcg32 rng(params.seed * 0x2545f491ull + 77);
    const double slice_w = params.width * opt.scale;
    for (int k = 0; k < opt.slices; ++k) {
      SlicePlacement& at = placement[k];
      const double depth = rng.unit_double();  // 0 = front, 1 = back
      at.scale = opt.scale * (1.0 - 0.45 * depth);
      at.gain = 1.0 - 0.3 * depth;
      at.bottom = 0.06 * canvas_h * depth;
      at.mirror = rng.unit_double() < 0.5;
      const double jitter = (rng.unit_double() - 0.5) * 0.3 * opt.slice_spacing * slice_w;
      const double centre = slice_w * (0.5 + k * opt.slice_spacing) + jitter;
      at.left = centre - 0.5 * params.width * at.scale;
      // A grid whose top lies inside the canvas (the smaller slices farther
      // back) fades out below its top; every grid fades at its sides, where
      // slices overlap.
      at.fade_sides = opt.slice_edge_fade;
      if (at.bottom + params.height * at.scale < canvas_h - 1.0)
        at.fade_top = 2.0 * opt.slice_edge_fade;
    }
  }
  std::vector<float> canvas;
  const FuelBed bed = hearth_fuel_bed(canvas_w, canvas_h, params.seed, opt.back_logs);
  const RadianceTable table(params.t_ambient, t_ref);

  FieldFrame field;
  field.t_ambient = params.t_ambient;
  field.t_reference = t_ref;
  field.has_velocity = true;
  const FluidSolver& solver = solvers.front();
  for (int f = 0; f < opt.frames; ++f) {
    Image img;
    if (opt.slices > 1) {
      // The shutter is open the whole frame: the picture is the mean of the
      // substeps' light, so fast tongues blur along their motion as on video.
      canvas.assign(static_cast<size_t>(canvas_w) * canvas_h, 0.0f);
      Camera cam = opt.camera;
      const int open_substeps =
          std::clamp(static_cast<int>(std::lround(opt.shutter * opt.substeps)), 1, opt.substeps);
      cam.exposure /= open_substeps;
      for (int sub = 0; sub < opt.substeps; ++sub) {
        one_step();
        if (sub < opt.substeps - open_substeps) continue;  // the shutter is still closed
        const double t = opt.warmup + (f + (sub + 0.5) / opt.substeps) / opt.fps;
        for (int k = 0; k < opt.slices; ++k) {
          SlicePlacement at = placement[k];
          if (opt.slice_flicker > 0.0)
            at.gain *= std::max(
                0.0, 1.0 + opt.slice_flicker * pink_flicker(params.seed * 131 + 7 * k + 3, t));
          add_radiance(solvers[k].temperature(), &solvers[k].fuel(), table, cam, at, canvas_w,
                       canvas_h, canvas);
        }
      }
      if (opt.fuel_bed) draw_fuel_bed(bed, opt.warmup + f / opt.fps, canvas_w, canvas_h, canvas);
      img = finish_radiance(canvas, canvas_w, canvas_h, opt.camera);
    } else if (opt.radiance) {
      for (int k = 0; k < opt.substeps; ++k) one_step();
      img = render_radiance(solver.temperature(), params.t_ambient, t_ref, opt.colour, opt.camera,
                            opt.scale, &solver.fuel());
    } else {
      img =
          render_temperature(solver.temperature(), params.t_ambient, t_ref, opt.colour, opt.scale);
    }
    write_png(frame_path(opt.out_dir, f), img);
    if (opt.write_fields) {
      field.index = static_cast<uint32_t>(f);
      field.time = f / opt.fps;
      field.temperature = solver.temperature();
      solver.cell_velocity(field.u, field.v);
      write_field_file(field_path(opt.out_dir, f), field);
    }
    if (progress) progress(f + 1, opt.frames);
  }

  SimManifest m;
  m.name = opt.name;
  if (m.name.empty()) {
    fs::path d = fs::absolute(opt.out_dir).lexically_normal();
    if (d.filename().empty()) d = d.parent_path();
    m.name = d.filename().string();
  }
  m.command = opt.command;
  m.frames = opt.frames;
  m.fps = opt.fps;
  m.width = opt.slices > 1 ? canvas_w : params.width * opt.scale;
  m.height = params.height * opt.scale;
  m.colour = opt.colour == ColourMode::kGray ? "gray" : "blackbody";
  m.has_fields = opt.write_fields;
  m.grid_width = params.width;
  m.grid_height = params.height;
  m.t_ambient = params.t_ambient;
  m.t_reference = t_ref;
  write_manifest(opt.out_dir, m);
  sum.t_reference = t_ref;
  sum.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return sum;
}

}  // namespace candela::fluid
