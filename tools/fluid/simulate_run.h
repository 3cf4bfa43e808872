// Runs a FluidSolver for a number of frames and writes the clip folder
// described in sim_dataset.h. Shared by `candela-tool simulate`, the tests and
// the benchmarks.
#pragma once

#include <functional>
#include <string>

#include "colour_map.h"
#include "fluid_solver.h"

namespace candela::fluid {

struct SimulateOptions {
  FluidParams params;
  int frames = 120;
  double fps = 30.0;
  int substeps = 2;     // solver steps per frame
  double warmup = 3.0;  // seconds simulated before the first frame
  ColourMode colour = ColourMode::kGray;
  // Frames show the normalised temperature (false) or what a camera sees of
  // the hot gas: black-body luminance, exposure and soft clip (true).
  bool radiance = false;
  Camera camera;
  int scale = 1;  // image pixels per cell
  // Slices: this many independent simulations of the preset (seeds differ),
  // placed side by side and in depth on one wider canvas and added as light
  // (gray radiance only). A 2-D plume merges into one sheet; real fire is
  // many thin tongues side by side, which this gives.
  int slices = 1;
  double slice_spacing = 0.5;  // distance between slice centres, in slice widths
  // Each slice's light flickers on its own by this depth (std of the gain,
  // 0..0.5), with pink (1/f) noise from 0.75 to 24 Hz: the many small
  // pockets of a real fire ignite and die out faster than a coarse 2-D
  // simulation resolves, so its brightness, sway and width flicker with
  // near-1/f spectra (the real fires' slopes are -0.8..-1.3; the slices alone
  // give -2.3..-2.8).
  double slice_flicker = 0.0;
  // Each slice's clock runs at its own seeded rate, spread evenly over
  // 1 - S .. 1 + S (0..0.6): real tongues differ in size, and a smaller
  // flame puffs faster (frequency ~ 1/sqrt(size)), so a fire's brightness has
  // no single puffing frequency. Identical slices all puff at one rate and
  // give the brightness spectrum a peak real fires do not have.
  double slice_rates = 0.0;
  // Each slice's light fades out over this share of its grid at the sides
  // (and twice that below its top where the top is inside the canvas), so
  // gas leaving a grid does not end along a straight line.
  double slice_edge_fade = 0.0;
  // Slices: the share of each frame the shutter is open (the last substeps'
  // light is averaged). Each substep is one sharp picture, so a long shutter
  // over few substeps shows a fast tongue as a few stacked copies; a short
  // one shows it crisp.
  double shutter = 1.0;
  // Logs and coals around the flames (fuel_bed.h), drawn on the slices' canvas.
  bool fuel_bed = false;
  bool back_logs = true;  // the bed's two logs behind the flames (fuel_bed.h)
  bool write_fields = true;
  double t_reference = 0.0;  // 0 = the hottest cell after the warm-up
  std::string out_dir;
  std::string name;     // clip name; empty = the folder's name
  std::string command;  // recorded in the manifest
};

struct SimulateSummary {
  int steps = 0;
  int max_pressure_iterations = 0;
  double max_relative_residual = 0.0;  // max over steps of max|h div u| / max|u|
  int unconverged_steps = 0;
  double seconds = 0.0;
  double t_reference = 0.0;  // K: the temperature shown as full brightness
};

// Progress: called after each frame with (frames done, frames total).
using Progress = std::function<void(int, int)>;

// Throws std::invalid_argument for bad options, RuntimeError for I/O.
SimulateSummary run_simulation(const SimulateOptions& opt, const Progress& progress = {});

// Presets the recipe and users start from: "candle" or "fireplace" (coarse,
// semi-Lagrangian, direct heating), "fire" (log fire) or "wick" (candle
// flame): fine grids, MacCormack advection, fuel burning to heat.
// Throws std::invalid_argument for an unknown name.
FluidParams preset_params(const std::string& name);

}  // namespace candela::fluid
