// A gust hitting the fire: band-passed noise whose level follows how far the
// wind at the flames (SoundCue::wind) has risen above its recent level, and
// whose pitch rises with it.
#pragma once

#include <cstdint>

#include "sound/dsp.h"

namespace candela {

class Whoosh {
 public:
  Whoosh(uint64_t seed, float level, int steps_per_second);
  // The wind this step, m/s.
  void set_wind(float wind);
  void render(float* out, int n);
  float gust() const { return gust_; }  // m/s above the recent level, for tests

 private:
  dsp::WhiteNoise noise_;
  dsp::BandPass band_;
  dsp::OnePole gain_;
  float level_;
  float baseline_ = 0, baseline_k_ = 0;  // the recent wind: a ~4 s follower
  float gust_ = 0, target_ = 0;
  float centre_ = 0;
};

}  // namespace candela
