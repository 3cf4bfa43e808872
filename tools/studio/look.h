// What the studio lets a user edit on the playing flame: the colour and glow
// (the eigenflame element's keys) and the weights.
#pragma once

#include <array>
#include <vector>

#include "elements/eigenflame/weight_edits.h"

namespace candela::studio {

struct Look {
  float hue = 28;  // degrees (HLS)
  // The hue at full brightness (the element's `hue_top`; it moves there with
  // the cube of the gray); until set, the hue throughout, as the element's default.
  bool has_hue_top = false;
  float hue_top = 28;         // degrees
  float saturation = 0.9f;    // 0..1
  float brightness = 1.0f;    // 0..16
  float glow_radius = 0.06f;  // fraction of the flame height, 0..1
  float glow_strength = 0;    // 0..8
  // The element's `transfer`: evenly spaced colour stops (RGB 0..1), dark to
  // bright, used instead of HLS when there are at least two.
  static constexpr size_t kMaxStops = 8;
  std::vector<std::array<float, 3>> transfer;
  bool operator==(const Look&) const = default;
};

// The weight edits: offsets of the first kShapeWeights weights in standard
// deviations of that weight over the model's frames, and one scale of all the
// detail weights beyond them: the eigenflame element's `weight_offsets` and
// `detail_scale`, applied by the same function (apply_weight_edits).
using WeightEdits = candela::EigenWeightEdits;

struct Edits {
  WeightEdits weights;
  Look look;
  bool operator==(const Edits&) const = default;
};

}  // namespace candela::studio
