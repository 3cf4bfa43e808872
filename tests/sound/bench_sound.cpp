// The synthesiser's cost: CPU per second of sound (issue 18's target: under
// 2% of one Pi-class core). Each iteration renders one second, 60 steps of
// 800 samples, as the audio thread does (the output's int16 conversion and
// device write are not included).
#include <benchmark/benchmark.h>

#include <vector>

#include "sound/sound_synth.h"

namespace candela {
namespace {

void run(benchmark::State& state, SoundCue cue) {
  SoundSettings s;
  s.enabled = true;
  SoundSynth synth(s, 60, 1);
  std::vector<float> buf(SoundSynth::kMaxStepSamples);
  uint64_t step = 0;
  for (auto _ : state) {
    for (int i = 0; i < 60; ++i, ++step) {
      SoundCue c = cue;
      c.blowouts = cue.blowouts && step % 120 == 0;
      synth.render_step(c, buf);
      benchmark::DoNotOptimize(buf.data());
    }
  }
  // One iteration is one second of sound: its CPU time is the share of a
  // core the audio thread's synthesis takes (1 ms: 0.1%).
  state.SetItemsProcessed(state.iterations() * 48000);
}

// A fireplace at its mean: roar, default crackle/pop/knock rates, calm air.
void BM_SoundFireplace(benchmark::State& state) {
  SoundCue c;
  c.fire = Fixed::from_int(2);
  c.activity = Fixed::from_int(2);
  run(state, c);
}
BENCHMARK(BM_SoundFireplace);

// A fanned fire: three times the activity, a gust whooshing.
void BM_SoundFannedFire(benchmark::State& state) {
  SoundCue c;
  c.fire = Fixed::from_int(3);
  c.activity = Fixed::from_int(6);
  c.wind = Fixed::from_int(3);
  run(state, c);
}
BENCHMARK(BM_SoundFannedFire);

// Candles: silent beds, a few sputters and a puff every 2 s.
void BM_SoundCandles(benchmark::State& state) {
  SoundCue c;
  c.sputters = 2;
  c.lit = 7;
  c.blowouts = 1;
  run(state, c);
}
BENCHMARK(BM_SoundCandles);

}  // namespace
}  // namespace candela
