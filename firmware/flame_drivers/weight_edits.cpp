#include "flame_drivers/weight_edits.h"

#include <algorithm>
#include <cmath>

#include "model/flame_model.h"

namespace candela {

bool EigenWeightEdits::identity() const {
  return detail_scale == 1.0f &&
         std::all_of(offset_sigma.begin(), offset_sigma.end(), [](float v) { return v == 0; });
}

std::vector<float> weight_sigmas(const model::FlameModel& m) {
  const int e = m.components(), f = m.frames();
  std::vector<float> sigma(static_cast<size_t>(e), 0.0f);
  for (int k = 0; k < e; ++k) {
    double s = 0, s2 = 0;
    for (int i = 0; i < f; ++i) {
      const double w = m.weights_of(i)[static_cast<size_t>(k)];
      s += w;
      s2 += w * w;
    }
    const double mean = f > 0 ? s / f : 0;
    sigma[static_cast<size_t>(k)] =
        static_cast<float>(std::sqrt(std::max(0.0, f > 0 ? s2 / f - mean * mean : 0.0)));
  }
  return sigma;
}

void apply_weight_edits(std::span<const float> base, std::span<const float> sigma,
                        const EigenWeightEdits& edits, std::span<float> out) {
  for (size_t k = 0; k < out.size(); ++k) {
    const float b = k < base.size() ? base[k] : 0.0f;
    if (k < static_cast<size_t>(EigenWeightEdits::kShapeWeights)) {
      const float s = k < sigma.size() ? sigma[k] : 0.0f;
      out[k] = b + edits.offset_sigma[k] * s;
    } else {
      out[k] = b * edits.detail_scale;
    }
  }
}

}  // namespace candela
