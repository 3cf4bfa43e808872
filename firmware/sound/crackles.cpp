#include "sound/crackles.h"

namespace candela {

FireEvents::FireEvents(uint64_t seed, Fixed crackle_rate, Fixed pop_rate, Fixed knock_rate,
                       float level)
    : crackle_clock_(seed, 101),
      pop_clock_(seed, 102),
      knock_clock_(seed, 103),
      crackle_rate_(crackle_rate),
      pop_rate_(pop_rate),
      knock_rate_(knock_rate),
      shape_rng_(seed, 104),
      level_(level) {}

float FireEvents::uniform() {
  return static_cast<float>(shape_rng_.next_u32() >> 8) * (1.0f / 16777216.0f);
}

void FireEvents::step(Fixed activity, int n, ImpulseVoices& voices) {
  if (activity.raw < 0) activity = Fixed{};
  crackle_clock_.set_rate(crackle_rate_ * activity);
  pop_clock_.set_rate(pop_rate_ * activity);
  knock_clock_.set_rate(knock_rate_ * activity);
  crackle_clock_.run(n, [&](int at) {
    ++crackles_;
    ImpulseShape s;
    // Loudness spread over ~20 dB, mostly quiet ones (u^2).
    const float u = uniform();
    s.amplitude = level_ * (0.04f + 0.36f * u * u);
    s.centre_hz = 1500.0f + 5500.0f * uniform();
    s.q = 1.5f + 3.0f * uniform();
    s.attack_s = 0.0001f;
    s.decay_s = 0.0006f + 0.0025f * uniform();
    s.noise = 1.0f;
    s.ring_gain = 2.5f;
    s.strikes = 1 + static_cast<int>(uniform() * 4.99f);
    s.strike_gap_min = 40;
    s.strike_gap_max = 40 + static_cast<int>(uniform() * 600);
    voices.start(s, at);
  });
  pop_clock_.run(n, [&](int at) {
    ++pops_;
    ImpulseShape s;
    s.amplitude = level_ * (0.35f + 0.35f * uniform());
    s.centre_hz = 450.0f + 900.0f * uniform();
    s.q = 2.0f + 2.0f * uniform();
    s.attack_s = 0.0002f;
    s.decay_s = 0.012f + 0.03f * uniform();
    s.noise = 0.6f;
    s.ring_gain = 2.0f;
    s.strikes = 1;
    voices.start(s, at);
  });
  knock_clock_.run(n, [&](int at) {
    ++knocks_;
    ImpulseShape s;
    s.amplitude = level_ * (0.25f + 0.25f * uniform());
    s.centre_hz = 70.0f + 90.0f * uniform();
    s.q = 18.0f + 20.0f * uniform();  // rings Q / (pi f): ~0.05..0.15 s
    s.attack_s = 0.0005f;
    s.decay_s = 0.02f;
    s.noise = 0.15f;
    s.ring_gain = 1.0f;
    s.strikes = 1 + static_cast<int>(uniform() * 1.6f);  // sometimes a double knock
    s.strike_gap_min = 2400;
    s.strike_gap_max = 7200;
    voices.start(s, at);
  });
}

}  // namespace candela
