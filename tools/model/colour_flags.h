// The colour flags of the subcommands that render a model's frames
// (render-weights, story): hue, saturation and glow, each defaulting to the
// model's own colour, as the runtime shows it.
#pragma once

#include <CLI/CLI.hpp>
#include <limits>

#include "core/image.h"
#include "model/flame_model.h"
#include "render.h"

namespace candela::tools {

struct ColourFlags {
  float hue = -1, saturation = -1, glow_radius = -1, glow = -1;  // < 0: the model's
  float hue_top = -1;  // < 0: the hue throughout (the model has one hue)

  void add_to(CLI::App& app) {
    app.add_option("--hue", hue, "hue in degrees (default: the model's, as the runtime)");
    app.add_option("--hue-top", hue_top,
                   "hue in degrees where the flame nears white (the eigenflame key hue_top; "
                   "default: the hue throughout)")
        ->check(CLI::Range(0.0, 360.0));
    app.add_option("--saturation", saturation, "saturation 0..1 (default: the model's)");
    app.add_option("--glow-radius", glow_radius,
                   "glow radius, fraction of the height (default: the model's)");
    app.add_option("--glow", glow, "glow strength (default: the model's; 0: none)");
  }
  // A reconstructed gray frame (0..255) coloured with these flags over the
  // model's defaults.
  Image colourise(const float* gray, int width, int height,
                  const model::ColourDefaults& model) const {
    return tools::colourise(gray, width, height, hue >= 0 ? hue : model.hue,
                            saturation >= 0 ? saturation : model.saturation,
                            glow_radius >= 0 ? glow_radius : model.glow_radius,
                            glow >= 0 ? glow : model.glow_strength, model.black_level,
                            hue_top >= 0 ? hue_top : std::numeric_limits<float>::quiet_NaN());
  }
};

}  // namespace candela::tools
