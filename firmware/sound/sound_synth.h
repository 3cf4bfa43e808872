// The scene's sound, one animation step at a time: each SoundCue becomes
// exactly that step's samples (800 at 60 steps/s and 48 kHz; rates that do
// not divide 48000 alternate lengths), so a headless render's audio is
// fixed by the seed and the cues, whatever the wall clock did.
//
//   fire  -> RoarBed (level), FireEvents (crackles, pops, knocks at rate x activity)
//   wind  -> Whoosh (the rise above the recent wind)
//   candles -> CandleSounds (sputters, blow-out puffs)
//
// Allocation-free after construction; mono float in -1..1 (soft-clipped).
#pragma once

#include <cstdint>
#include <span>

#include "sound/candle_sounds.h"
#include "sound/crackles.h"
#include "sound/impulse_voice.h"
#include "sound/roar.h"
#include "sound/sound_cue.h"
#include "sound/sound_settings.h"
#include "sound/whoosh.h"

namespace candela {

class SoundSynth {
 public:
  static constexpr int kSampleRate = dsp::kSampleRate;
  static constexpr int kMaxStepSamples = kSampleRate / 10;  // 10 steps/s at least (scene_file.cpp)

  SoundSynth(const SoundSettings& settings, int steps_per_second, uint64_t seed);
  // Samples the next step spans.
  int next_step_samples() const;
  // Renders the next step for `cue` into out[0 .. next_step_samples()); returns the count.
  int render_step(const SoundCue& cue, std::span<float> out);

  uint64_t steps() const { return steps_; }
  uint64_t samples() const { return samples_; }
  const FireEvents& fire_events() const { return fire_; }
  const CandleSounds& candle_sounds() const { return candles_; }
  const Whoosh& whoosh() const { return whoosh_; }
  // The master gain applied to the last sample rendered (it glides toward
  // each cue's volume with a 15 ms time constant).
  float gain() const { return gain_; }
  static constexpr float kVolumeGlideSeconds = 0.015f;

 private:
  int steps_per_second_;
  float volume_;  // the [sound] volume: the target while cues carry none
  float gain_;    // the master gain now
  float glide_;   // per-sample fraction of the way to the target
  ImpulseVoices voices_;
  RoarBed roar_;
  FireEvents fire_;
  Whoosh whoosh_;
  CandleSounds candles_;
  uint64_t steps_ = 0, samples_ = 0;
};

}  // namespace candela
