// Candles are silent while they burn calmly. A flame clinging to its wick in
// strong wind sputters (tiny soft crackles, 0.8..2.5 kHz, `sputter_rate` per
// second per such candle); a candle blown out gives a puff (a breath of
// low-passed noise: 4 ms rise, ~0.1 s fall), starting within 2 ms of the
// step in which it went out.
#pragma once

#include <cstdint>

#include "core/fixed.h"
#include "sound/event_clock.h"
#include "sound/impulse_voice.h"
#include "sound/sound_cue.h"

namespace candela {

class CandleSounds {
 public:
  CandleSounds(uint64_t seed, Fixed sputter_rate, float level);
  void step(const SoundCue& cue, int n, ImpulseVoices& voices);
  uint64_t puffs() const { return puffs_; }
  uint64_t sputters() const { return sputters_; }

 private:
  float uniform();
  EventClock sputter_clock_;
  Fixed sputter_rate_;
  Pcg32 shape_rng_;
  float level_;
  uint64_t puffs_ = 0, sputters_ = 0;
};

}  // namespace candela
