// One short sound event (a crackle, pop, knock, sputter or puff): noise or a
// single impulse through a band-pass, shaped by an attack/decay envelope,
// optionally re-struck a few times (a crackle is a burst of clicks). A fixed
// pool of voices plays them; a new event takes a free voice or the quietest.
#pragma once

#include <array>
#include <cstdint>

#include "sound/dsp.h"

namespace candela {

struct ImpulseShape {
  float amplitude = 0.5f;
  float centre_hz = 3000, q = 2;  // the band-pass the excitation rings through
  float attack_s = 0.0005f;       // envelope rise
  float decay_s = 0.003f;         // envelope fall (1/e)
  float noise = 1.0f;             // noise excitation share (0: impulse only, a ringing tone)
  // Impulse share at each click (scaled by q, so a band-pass rings at about `amplitude`).
  float click = 1.0f;
  float ring_gain = 1.0f;                         // gain on the band-pass output
  int strikes = 1;                                // clicks in the burst
  int strike_gap_min = 48, strike_gap_max = 480;  // samples between clicks
};

class ImpulseVoices {
 public:
  static constexpr int kVoices = 24;

  explicit ImpulseVoices(uint64_t seed) : noise_(seed), rng_(seed ^ 0xC3A5C85C97CB3127ULL) {}

  // Starts `shape` `delay` samples into the next render().
  void start(const ImpulseShape& shape, int delay);
  // Adds the voices' next `n` samples to out.
  void render(float* out, int n);
  int active() const;

 private:
  struct Voice {
    bool on = false;
    int delay = 0;
    ImpulseShape shape;
    dsp::BandPass filter;
    float env = 0, target = 0, attack_k = 1, decay_k = 0;
    int strikes_left = 0, next_strike = 0;
    float impulse = 0;      // pending impulse excitation
    int age = 0, life = 0;  // samples played, and after how many it is silent
  };
  void strike(Voice& v);
  uint32_t draw(uint32_t bound);

  std::array<Voice, kVoices> voices_{};
  dsp::WhiteNoise noise_;
  uint64_t rng_;
};

}  // namespace candela
