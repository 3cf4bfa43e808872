// The synthesiser against what a listener cares about: crackles at the
// configured rate, a roar that follows the fire's brightness, a puff right
// after a blow-out, a whoosh when a gust hits, sound that never repeats, and
// the same samples for the same seed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "sound/sound_synth.h"
#include "support/correlation.h"

namespace candela {
namespace {

#if defined(__SANITIZE_ADDRESS__)
constexpr int kScale = 6;  // the sanitizers run the same checks on less sound
#else
constexpr int kScale = 1;
#endif

SoundCue fire_cue(double fire, double activity) {
  SoundCue c;
  c.fire = Fixed::from_double(fire);
  c.activity = Fixed::from_double(activity);
  return c;
}

double rms(const float* x, int n) {
  double s = 0;
  for (int i = 0; i < n; ++i) s += static_cast<double>(x[i]) * x[i];
  return std::sqrt(s / n);
}

TEST(SoundSynth, StepsSpanTheirShareOfSamples) {
  SoundSettings s;
  s.enabled = true;
  SoundSynth at60(s, 60, 1);
  std::vector<float> buf(SoundSynth::kMaxStepSamples);
  for (int i = 0; i < 120; ++i) EXPECT_EQ(at60.render_step({}, buf), 800);
  // 11 steps/s does not divide 48000: lengths alternate, a second is exact.
  SoundSynth at11(s, 11, 1);
  int total = 0;
  for (int i = 0; i < 11; ++i) {
    const int n = at11.render_step({}, buf);
    EXPECT_TRUE(n == 4363 || n == 4364) << n;
    total += n;
  }
  EXPECT_EQ(total, 48000);
}

// Crackles are a Poisson process at crackle_rate x activity: the count over
// a minute lies within 4 standard deviations of rate x time, per-second
// counts scatter as Poisson counts do (variance / mean near 1), and half
// the activity gives half the rate.
TEST(SoundSynth, CrackleRateMatchesTheConfiguredRate) {
  SoundSettings s;
  s.enabled = true;
  s.crackle_rate = Fixed::from_int(12);
  s.pop_rate = Fixed{};
  s.knock_rate = Fixed{};
  const int seconds = 60 / kScale;
  for (const double activity : {1.0, 0.5}) {
    SCOPED_TRACE(activity);
    SoundSynth synth(s, 60, 7);
    std::vector<float> buf(SoundSynth::kMaxStepSamples);
    std::vector<double> per_second;
    uint64_t last = 0;
    for (int i = 0; i < seconds * 60; ++i) {
      synth.render_step(fire_cue(1, activity), buf);
      if (i % 60 == 59) {
        per_second.push_back(static_cast<double>(synth.fire_events().crackles() - last));
        last = synth.fire_events().crackles();
      }
    }
    const double expected = 12.0 * activity * seconds;
    const double got = static_cast<double>(synth.fire_events().crackles());
    EXPECT_NEAR(got, expected, 4 * std::sqrt(expected));
    double mean = 0, var = 0;
    for (double c : per_second) mean += c;
    mean /= per_second.size();
    for (double c : per_second) var += (c - mean) * (c - mean);
    var /= per_second.size() - 1;
    EXPECT_GT(var / mean, 0.4);
    EXPECT_LT(var / mean, 1.8);
  }
}

// Pops and knocks follow their own, lower rates.
TEST(SoundSynth, PopAndKnockRates) {
  SoundSettings s;
  s.enabled = true;
  s.crackle_rate = Fixed{};
  s.pop_rate = Fixed::from_int(2);
  s.knock_rate = Fixed::from_ratio(1, 2);
  SoundSynth synth(s, 60, 3);
  std::vector<float> buf(SoundSynth::kMaxStepSamples);
  const int seconds = 120 / kScale;
  for (int i = 0; i < seconds * 60; ++i) synth.render_step(fire_cue(1, 1), buf);
  const double pops = 2.0 * seconds, knocks = 0.5 * seconds;
  EXPECT_NEAR(static_cast<double>(synth.fire_events().pops()), pops, 4 * std::sqrt(pops));
  EXPECT_NEAR(static_cast<double>(synth.fire_events().knocks()), knocks, 4 * std::sqrt(knocks));
}

// The roar's loudness follows a driven brightness (a slow swell plus random
// jumps, as a fire's light moves): over 200 ms windows (12 steps; a single
// step of low rumble is too short to measure its own level well) the
// correlation is above 0.9, and twice the fire is about twice the level.
TEST(SoundSynth, RoarLevelFollowsBrightness) {
  SoundSettings s;
  s.enabled = true;
  s.crackle_rate = s.pop_rate = s.knock_rate = Fixed{};
  SoundSynth synth(s, 60, 11);
  std::vector<float> buf(SoundSynth::kMaxStepSamples);
  Pcg32 rng(5);
  std::vector<double> brightness, level;
  double jump = 0, b_sum = 0, e_sum = 0;
  for (int i = 0; i < 60 * 60 / kScale; ++i) {
    if (i % 24 == 0) jump = 0.4 * rng.unit_double();
    const double b = 0.7 + 0.3 * std::sin(2 * 3.14159265 * i / 120.0) + jump;
    const int n = synth.render_step(fire_cue(b, 0), buf);
    if (i < 30) continue;  // the level's smoothing settles (30 % 12 == 6: whole windows)
    b_sum += b;
    e_sum += rms(buf.data(), n) * rms(buf.data(), n);
    if (i % 12 == 5) {
      brightness.push_back(b_sum / 12);
      level.push_back(std::sqrt(e_sum / 12));
      b_sum = e_sum = 0;
    }
  }
  EXPECT_GT(test::correlation(brightness, level), 0.9);

  auto mean_level = [&](double fire) {
    SoundSynth fresh(s, 60, 11);
    double sum = 0;
    for (int i = 0; i < 600 / kScale; ++i) {
      const int n = fresh.render_step(fire_cue(fire, 0), buf);
      if (i >= 30) sum += rms(buf.data(), n);
    }
    return sum;
  };
  const double ratio = mean_level(2.0) / mean_level(1.0);
  EXPECT_GT(ratio, 1.7);
  EXPECT_LT(ratio, 2.3);
}

// Silence before, a puff right after: the first loud sample comes within
// 50 ms of the start of the step in which the candle went out (the frame
// that shows it out), and it is clearly heard.
TEST(SoundSynth, BlowOutPuffWithin50ms) {
  SoundSettings s;
  s.enabled = true;
  SoundSynth synth(s, 60, 21);
  std::vector<float> out;
  std::vector<float> buf(SoundSynth::kMaxStepSamples);
  SoundCue calm;
  calm.lit = 1;
  const int blow_step = 90;
  for (int i = 0; i < 150; ++i) {
    SoundCue c = calm;
    if (i == blow_step) c.blowouts = 1, c.lit = 0;
    if (i > blow_step) c.lit = 0;
    const int n = synth.render_step(c, buf);
    out.insert(out.end(), buf.begin(), buf.begin() + n);
  }
  const size_t event = static_cast<size_t>(blow_step) * 800;
  float before = 0, peak = 0;
  for (size_t i = 0; i < event; ++i) before = std::max(before, std::fabs(out[i]));
  for (size_t i = event; i < out.size(); ++i) peak = std::max(peak, std::fabs(out[i]));
  EXPECT_EQ(before, 0.0f) << "a calm candle is silent";
  EXPECT_GT(peak, 0.05f) << "the puff is heard";
  size_t onset = event;
  while (onset < out.size() && std::fabs(out[onset]) < 0.25f * peak) ++onset;
  EXPECT_LT(static_cast<double>(onset - event) / 48000.0, 0.050);
  EXPECT_EQ(synth.candle_sounds().puffs(), 1u);
}

// A gust hitting (wind from 0 to 3 m/s) is heard: the half second after it
// is far louder than the calm before, and a steady wind fades back.
TEST(SoundSynth, GustWhooshes) {
  SoundSettings s;
  s.enabled = true;
  SoundSynth synth(s, 60, 4);
  std::vector<float> buf(SoundSynth::kMaxStepSamples);
  SoundCue c;
  double calm = 0, gust = 0, settled = 0;
  for (int i = 0; i < 60 * 20; ++i) {
    c.wind = Fixed::from_double(i >= 120 ? 3.0 : 0.2);
    const int n = synth.render_step(c, buf);
    const double r = rms(buf.data(), n);
    if (i >= 60 && i < 120) calm += r;
    if (i >= 125 && i < 155) gust += r * 2;  // 30 steps vs 60
    if (i >= 60 * 19) settled += r;
  }
  EXPECT_GT(gust, 5 * calm);
  EXPECT_LT(settled, 0.3 * gust) << "a steady wind is not a gust";
}

// No stretch of sound comes round again: over ten minutes of a fire at a
// constant level (the case a loop would show), no 10 ms block of samples
// equals any other, so no stretch of 1 s (100 blocks) can repeat.
TEST(SoundSynth, NeverRepeats) {
  SoundSettings s;
  s.enabled = true;
  SoundSynth synth(s, 60, 99);
  std::vector<float> buf(SoundSynth::kMaxStepSamples);
  std::vector<int16_t> pcm;
  std::unordered_map<uint64_t, uint32_t> seen;
  const int steps = 60 * 600 / (kScale * kScale);
  uint32_t block = 0, repeats = 0, silent = 0;
  for (int i = 0; i < steps; ++i) {
    const int n = synth.render_step(fire_cue(1, 1), buf);
    for (int k = 0; k < n; ++k) pcm.push_back(static_cast<int16_t>(buf[k] * 32767.0f));
    while (pcm.size() >= 480) {
      uint64_t h = 1469598103934665603ULL;  // FNV-1a of the block's samples
      bool quiet = true;
      for (int k = 0; k < 480; ++k) {
        h = (h ^ static_cast<uint16_t>(pcm[k])) * 1099511628211ULL;
        quiet = quiet && pcm[k] == 0;
      }
      silent += quiet;
      if (!seen.emplace(h, block).second) ++repeats;
      ++block;
      pcm.erase(pcm.begin(), pcm.begin() + 480);
    }
  }
  EXPECT_GT(block, 6000u / kScale);
  EXPECT_EQ(silent, 0u);
  EXPECT_EQ(repeats, 0u) << "of " << block << " blocks of 10 ms";
}

// The master volume (the control socket's `volume`, carried by each cue)
// reaches the mix: the same fire at 0.15 is a quarter as loud as at 0.6
// (RMS, within 3%), 0 is silent, and a jump of the volume glides: the gain
// moves at most 1/720 a sample (15 ms time constant), is part way after the
// first step and exactly there within 150 ms (the last 1e-4, -80 dB, is
// snapped).
TEST(SoundSynth, VolumeReachesTheMixAndGlides) {
  SoundSettings s;
  s.enabled = true;
  s.volume = 0.6f;
  SoundSynth full(s, 60, 5), quiet(s, 60, 5);
  std::vector<float> a(SoundSynth::kMaxStepSamples), b(a.size());
  double ra = 0, rb = 0;
  for (int i = 0; i < 600 / kScale; ++i) {
    SoundCue cue = fire_cue(1, 1);
    full.render_step(cue, a);
    cue.volume = 0.15f;
    const int n = quiet.render_step(cue, b);
    if (i == 0) {
      EXPECT_LT(quiet.gain(), 0.6f);
      EXPECT_GT(quiet.gain(), 0.15f) << "the first step glides, it does not jump";
    }
    if (i >= 9) {
      EXPECT_FLOAT_EQ(quiet.gain(), 0.15f);
      ra += rms(a.data(), n) * rms(a.data(), n);
      rb += rms(b.data(), n) * rms(b.data(), n);
    }
  }
  EXPECT_GT(ra, 1e-4) << "the fire is heard";
  EXPECT_NEAR(std::sqrt(rb / ra), 0.25, 0.25 * 0.03);

  // 0 -> 1 in one command: sample by sample, the gain never steps.
  SoundSynth up(s, 60, 6);
  SoundCue silent = fire_cue(1, 1);
  silent.volume = 0;
  for (int i = 0; i < 10; ++i) up.render_step(silent, a);
  EXPECT_EQ(up.gain(), 0.0f);
  EXPECT_EQ(rms(a.data(), 800), 0.0) << "volume 0 is silent";
  SoundCue loud = fire_cue(1, 1);
  loud.volume = 1;
  float last = up.gain();
  float max_step = 0;
  // One-sample steps are not the API; measure the gain per step and bound
  // each step's change by what the time constant allows over its 800 samples.
  for (int i = 0; i < 6; ++i) {
    up.render_step(loud, a);
    max_step = std::max(max_step, up.gain() - last);
    last = up.gain();
  }
  const float per_step_bound = 1.0f - std::exp(-800.0f / (SoundSynth::kVolumeGlideSeconds * 48000));
  EXPECT_LE(max_step, per_step_bound + 1e-4f);
  EXPECT_GT(max_step, 0.5f * per_step_bound);
  EXPECT_GT(last, 0.99f) << "there within 100 ms";
  // Within the first step after the change the waveform rises smoothly:
  // the first 48 samples (1 ms) carry at most 1 ms worth of glide (< 7%).
  SoundSynth edge(s, 60, 6);
  for (int i = 0; i < 10; ++i) edge.render_step(silent, a);
  edge.render_step(loud, a);
  float early = 0;
  for (int k = 0; k < 48; ++k) early = std::max(early, std::fabs(a[static_cast<size_t>(k)]));
  float later = 0;
  for (int k = 700; k < 800; ++k) later = std::max(later, std::fabs(a[static_cast<size_t>(k)]));
  EXPECT_LT(early, 0.3f * later) << "no click at the start of the glide";
}

TEST(SoundSynth, SameSeedSameSamples) {
  SoundSettings s;
  s.enabled = true;
  std::vector<float> a(SoundSynth::kMaxStepSamples), b(a.size()), c(a.size());
  SoundSynth x(s, 60, 42), y(s, 60, 42), z(s, 60, 43);
  size_t differ = 0;
  for (int i = 0; i < 600; ++i) {
    SoundCue cue = fire_cue(1 + 0.3 * std::sin(i * 0.05), 1);
    cue.wind = Fixed::from_int(i > 300 ? 3 : 0);
    cue.blowouts = i == 200;
    const int n = x.render_step(cue, a);
    y.render_step(cue, b);
    z.render_step(cue, c);
    ASSERT_EQ(std::vector<float>(a.begin(), a.begin() + n),
              std::vector<float>(b.begin(), b.begin() + n))
        << "step " << i;
    for (int k = 0; k < n; ++k) differ += a[static_cast<size_t>(k)] != c[static_cast<size_t>(k)];
  }
  EXPECT_GT(differ, 600u * 800 * 9 / 10) << "another seed, other sound";
}

}  // namespace
}  // namespace candela
