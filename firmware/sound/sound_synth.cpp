#include "sound/sound_synth.h"

#include <algorithm>
#include <cmath>

#include "core/random.h"

namespace candela {

// The parts draw from independent streams of the one seed (core/random.h).
SoundSynth::SoundSynth(const SoundSettings& s, int steps_per_second, uint64_t seed)
    : steps_per_second_(std::clamp(steps_per_second, 10, 1000)),
      volume_(s.volume),
      gain_(s.volume),
      glide_(1.0f - std::exp(-1.0f / (kVolumeGlideSeconds * static_cast<float>(kSampleRate)))),
      voices_(split_seed(seed, 1)),
      roar_(split_seed(seed, 2), s.roar),
      fire_(split_seed(seed, 3), s.crackle_rate, s.pop_rate, s.knock_rate, s.crackle),
      whoosh_(split_seed(seed, 4), s.whoosh, steps_per_second_),
      candles_(split_seed(seed, 5), s.sputter_rate, s.candle) {}

int SoundSynth::next_step_samples() const {
  // Step k ends at sample floor((k + 1) * rate / sps): no drift over any run.
  const uint64_t k = steps_;
  const auto sps = static_cast<uint64_t>(steps_per_second_);
  return static_cast<int>((k + 1) * kSampleRate / sps - k * kSampleRate / sps);
}

int SoundSynth::render_step(const SoundCue& cue, std::span<float> out) {
  const int n = std::min(next_step_samples(), static_cast<int>(out.size()));
  float* o = out.data();
  std::fill(o, o + n, 0.0f);
  roar_.set_fire(cue.fire.to_float());
  whoosh_.set_wind(cue.wind.to_float());
  fire_.step(cue.activity, n, voices_);
  candles_.step(cue, n, voices_);
  roar_.render(o, n);
  whoosh_.render(o, n);
  voices_.render(o, n);
  const float target = cue.volume >= 0 ? std::min(cue.volume, 1.0f) : volume_;
  if (gain_ == target) {
    for (int i = 0; i < n; ++i) o[i] = dsp::soft_clip(o[i] * gain_);
  } else {
    // A one-pole glide, sample by sample: a volume step never clicks.
    for (int i = 0; i < n; ++i) {
      gain_ += (target - gain_) * glide_;
      o[i] = dsp::soft_clip(o[i] * gain_);
    }
    if (std::fabs(gain_ - target) < 1e-4f) gain_ = target;  // -80 dB: inaudible
  }
  ++steps_;
  samples_ += static_cast<uint64_t>(n);
  return n;
}

}  // namespace candela
