#include "sound/candle_sounds.h"

namespace candela {

CandleSounds::CandleSounds(uint64_t seed, Fixed sputter_rate, float level)
    : sputter_clock_(seed, 201),
      sputter_rate_(sputter_rate),
      shape_rng_(seed, 202),
      level_(level) {}

float CandleSounds::uniform() {
  return static_cast<float>(shape_rng_.next_u32() >> 8) * (1.0f / 16777216.0f);
}

void CandleSounds::step(const SoundCue& cue, int n, ImpulseVoices& voices) {
  // More candles sputtering: more sputters, but not louder each.
  const int sputtering = cue.sputters > 64 ? 64 : cue.sputters;
  sputter_clock_.set_rate(sputter_rate_ * sputtering);
  sputter_clock_.run(n, [&](int at) {
    ++sputters_;
    ImpulseShape s;
    s.amplitude = level_ * (0.03f + 0.06f * uniform());
    s.centre_hz = 800.0f + 1700.0f * uniform();
    s.q = 1.2f + uniform();
    s.attack_s = 0.0003f;
    s.decay_s = 0.002f + 0.004f * uniform();
    s.ring_gain = 2.0f;
    s.click = 0.3f;
    s.strikes = 1 + static_cast<int>(uniform() * 2.99f);
    s.strike_gap_min = 200;
    s.strike_gap_max = 1200;
    voices.start(s, at);
  });
  const int blown = cue.blowouts > 8 ? 8 : cue.blowouts;  // a row blown out: a few puffs, not 400
  for (int i = 0; i < blown; ++i) {
    ++puffs_;
    ImpulseShape s;
    s.amplitude = level_ * (0.22f + 0.1f * uniform()) / (1.0f + 0.3f * i);
    s.centre_hz = 500.0f + 500.0f * uniform();
    s.q = 0.6f;
    s.attack_s = 0.004f;
    s.decay_s = 0.07f + 0.05f * uniform();
    s.ring_gain = 2.5f;
    s.click = 0.0f;
    s.strikes = 1;
    voices.start(s, static_cast<int>(uniform() * 96));  // within 2 ms of the step's start
  }
}

}  // namespace candela
