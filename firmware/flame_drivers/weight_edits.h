// Edits of an eigen-flame's weights, as the studio's sliders make them and
// the eigenflame element's `weight_offsets` / `detail_scale` keys play them:
// the first kShapeWeights weights moved by a number of standard deviations of
// that weight (over the model's frames), and every weight from kShapeWeights
// on scaled by one factor. One function applies them for both, so a saved
// scene shows the flame the studio showed.
#pragma once

#include <array>
#include <span>
#include <vector>

namespace candela {

namespace model {
class FlameModel;
}

struct EigenWeightEdits {
  static constexpr int kShapeWeights = 50;
  static constexpr float kMaxOffset = 5.0f;       // standard deviations, +-
  static constexpr float kMaxDetailScale = 4.0f;  // 0..4
  std::array<float, kShapeWeights> offset_sigma{};
  float detail_scale = 1.0f;
  // No edit at all: the weights play as they are.
  bool identity() const;
  bool operator==(const EigenWeightEdits&) const = default;
};

// Each weight's standard deviation over the model's frames (the offsets' unit).
std::vector<float> weight_sigmas(const model::FlameModel& m);

// out[k] = base[k] + offset_sigma[k] * sigma[k] for k < kShapeWeights,
// base[k] * detail_scale beyond. out.size() weights are written; base and
// sigma may be shorter (missing entries count as 0).
void apply_weight_edits(std::span<const float> base, std::span<const float> sigma,
                        const EigenWeightEdits& edits, std::span<float> out);

}  // namespace candela
