// What the studio lets a user edit on the playing flame: the colour and glow
// (the eigenflame element's keys) and the weights.
#pragma once

#include <array>
#include <cmath>
#include <vector>

#include "flame_drivers/weight_edits.h"

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
  // The element's `transfer`: colour stops (RGB 0..1), dark to bright, used
  // instead of HLS when there are at least two, each at its place in
  // transfer_at (0..1 of the gray, rising; as many as the stops).
  static constexpr size_t kMaxStops = 8;
  std::vector<std::array<float, 3>> transfer;
  std::vector<float> transfer_at;
  static std::vector<float> even_places(size_t n) {
    std::vector<float> p(n);
    for (size_t i = 0; i < n; ++i) p[i] = n > 1 ? static_cast<float>(i) / (n - 1) : 0.0f;
    return p;
  }
  // The stops evenly spaced (the element's plain `transfer`).
  bool evenly_spaced() const {
    if (transfer_at.size() != transfer.size()) return true;
    const auto even = even_places(transfer.size());
    for (size_t i = 0; i < even.size(); ++i)
      if (std::abs(transfer_at[i] - even[i]) > 1e-6f) return false;
    return true;
  }
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
