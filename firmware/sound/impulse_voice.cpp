#include "sound/impulse_voice.h"

#include <cmath>

#include "core/random.h"

namespace candela {

uint32_t ImpulseVoices::draw(uint32_t bound) {
  // SplitMix64: gaps between clicks (not event timing, which event_clock.h owns).
  const uint64_t z = splitmix64_mix(rng_ += kSplitMix64Gamma);
  return bound ? static_cast<uint32_t>(z % bound) : 0;
}

void ImpulseVoices::start(const ImpulseShape& shape, int delay) {
  Voice* pick = nullptr;
  for (auto& v : voices_)
    if (!v.on) {
      pick = &v;
      break;
    }
  if (!pick) {  // all busy: steal the quietest
    pick = &voices_[0];
    for (auto& v : voices_)
      if (v.env * v.shape.amplitude < pick->env * pick->shape.amplitude) pick = &v;
  }
  Voice& v = *pick;
  v = Voice{};
  v.on = true;
  v.delay = delay;
  v.shape = shape;
  v.filter.set(shape.centre_hz, shape.q);
  v.attack_k = dsp::OnePole::for_seconds(shape.attack_s);
  v.decay_k = std::exp(-1.0f / (shape.decay_s * dsp::kSampleRate));
  v.strikes_left = shape.strikes;
  v.next_strike = 0;
  // Long enough for the envelope and the band-pass's ringing (time constant
  // Q / (pi f)) to fall by ~100 dB after the last click.
  const float ring_s = shape.q / (dsp::kPi * shape.centre_hz);
  const float tail_s = 12.0f * (shape.decay_s > ring_s ? shape.decay_s : ring_s);
  v.life = static_cast<int>(tail_s * dsp::kSampleRate) + shape.strikes * shape.strike_gap_max;
}

void ImpulseVoices::strike(Voice& v) {
  // Each click a little weaker or stronger than the last.
  const float vary = 0.55f + 0.45f * static_cast<float>(draw(1024)) / 1024.0f;
  v.target = v.shape.amplitude * vary;
  v.impulse = v.target * v.shape.q * v.shape.click;  // a band-pass rings at about impulse / Q
  --v.strikes_left;
  const int span = v.shape.strike_gap_max - v.shape.strike_gap_min;
  v.next_strike = v.shape.strike_gap_min + static_cast<int>(draw(span > 0 ? span : 1));
}

void ImpulseVoices::render(float* out, int n) {
  for (auto& v : voices_) {
    if (!v.on) continue;
    int i = 0;
    if (v.delay >= n) {
      v.delay -= n;
      continue;
    }
    i = v.delay;
    v.delay = 0;
    for (; i < n; ++i) {
      if (v.strikes_left > 0 && v.next_strike-- <= 0) strike(v);
      // Attack toward the strike's level, then decay: env rises while
      // target > env, and the target itself decays.
      v.env += v.attack_k * (v.target - v.env);
      v.target *= v.decay_k;
      const float x = v.shape.noise * noise_.next() * v.env + v.impulse;
      v.impulse = 0;
      out[i] += v.shape.ring_gain * v.filter.run(x);
      ++v.age;
    }
    if (v.strikes_left <= 0 && v.age > v.life) v.on = false;
  }
}

int ImpulseVoices::active() const {
  int n = 0;
  for (const auto& v : voices_) n += v.on;
  return n;
}

}  // namespace candela
