#include "sound/roar.h"

namespace candela {

RoarBed::RoarBed(uint64_t seed, float level)
    : noise_(seed), swell_noise_(seed ^ 0x5DEECE66DULL), level_(level) {
  gain_ = dsp::OnePole(1.0f / (2 * dsp::kPi * 0.03f));  // ~30 ms: follows the flicker, no clicks
}

void RoarBed::set_fire(float fire) { target_ = level_ * (fire < 0 ? 0 : (fire > 4 ? 4 : fire)); }

void RoarBed::render(float* out, int n) {
  if (target_ == 0 && gain_.value() < 1e-7f) return;  // no fire: no work (candles)
  for (int i = 0; i < n; ++i) {
    const float g = gain_.low(target_);
    const float w = noise_.next();
    // Twice low-passed: a -12 dB/octave rumble; the swell (0.6 Hz noise,
    // magnified) breathes it by about +-8%.
    const float roar = low2_.low(low1_.low(w)) * 5.0f;
    const float swell = 1.0f + 22.0f * swell_.low(swell_noise_.next());
    const float hiss = hiss_low_.low(hiss_high_.high(noise_.next())) * 0.18f;
    out[i] += g * (roar * swell + hiss) * 0.22f;
  }
}

}  // namespace candela
