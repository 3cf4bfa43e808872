#include "sound/whoosh.h"

#include <cmath>

namespace candela {

Whoosh::Whoosh(uint64_t seed, float level, int steps_per_second) : noise_(seed), level_(level) {
  baseline_k_ = 1.0f - std::exp(-1.0f / (4.0f * static_cast<float>(steps_per_second)));
  gain_ = dsp::OnePole(1.0f / (2 * dsp::kPi * 0.05f));
  band_.set(400, 0.8f);
}

void Whoosh::set_wind(float wind) {
  // The baseline rises slowly and falls at once: a steady wind is quiet, a
  // gust is heard as it arrives and fades as the baseline catches up.
  baseline_ = wind < baseline_ ? wind : baseline_ + baseline_k_ * (wind - baseline_);
  gust_ = wind - baseline_;
  const float g = gust_ > 6 ? 6 : gust_;
  target_ = level_ * 0.15f * g;
  const float centre = 250.0f + 180.0f * g;
  if (std::fabs(centre - centre_) > 5.0f) {
    band_.set(centre, 0.7f);
    centre_ = centre;
  }
}

void Whoosh::render(float* out, int n) {
  if (target_ == 0 && gain_.value() < 1e-7f) return;  // calm air: no work
  for (int i = 0; i < n; ++i) out[i] += gain_.low(target_) * band_.run(noise_.next()) * 2.5f;
}

}  // namespace candela
