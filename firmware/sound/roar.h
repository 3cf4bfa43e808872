// The fire's bed: a low roar (noise low-passed twice, round 250 Hz, with a
// slow random swell) and a soft hiss (noise above ~3 kHz), both at a level
// that follows the fire's brightness (SoundCue::fire) step by step.
#pragma once

#include <cstdint>

#include "sound/dsp.h"

namespace candela {

class RoarBed {
 public:
  RoarBed(uint64_t seed, float level);
  // The level to reach over this step: fire = summed brightness (cue.fire).
  void set_fire(float fire);
  void render(float* out, int n);

 private:
  dsp::WhiteNoise noise_, swell_noise_;
  dsp::OnePole low1_{260}, low2_{260}, hiss_high_{3200}, hiss_low_{9000};
  dsp::OnePole swell_{0.6f};  // slow random swell of the roar
  dsp::OnePole gain_;         // the level, smoothed (no zipper noise)
  float level_ = 1.0f;
  float target_ = 0.0f;
};

}  // namespace candela
