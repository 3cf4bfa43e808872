// The outputs: a recording holds exactly the synthesiser's samples for the
// cues pushed (through the audio thread); ALSA plays through the real
// libasound API (its `file` plugin writes what was played to a file, read
// back here; no snd-aloop / snd-dummy module can be loaded on this host);
// a missing device is logged and the frame loop's side never waits.
#include <gtest/gtest.h>
#include <poll.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>
#include <vector>

#include "sound/sound_output.h"
#include "sound/sound_synth.h"

namespace candela {
namespace {

std::string temp_path(const char* name) {
  return ::testing::TempDir() + "candela-sound-" + std::to_string(getpid()) + "-" + name;
}

std::vector<char> read_all(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(f), {}};
}

SoundCue cue_at(int i) {
  SoundCue c;
  c.fire = Fixed::from_double(1.0 + 0.3 * std::sin(i * 0.1));
  c.activity = Fixed::from_int(1);
  c.wind = Fixed::from_int(i > 100 ? 3 : 0);
  c.blowouts = i == 50;
  return c;
}

TEST(SoundOutput, RecordingHoldsExactlyTheStepsSamples) {
  SoundSettings s;
  s.enabled = true;
  const std::string path = temp_path("rec.wav");
  const int steps = 240;
  {
    auto rec = open_sound_recording(s, 60, 77, path);
    for (int i = 0; i < steps; ++i) rec->push(cue_at(i));
    rec->finish();
    EXPECT_EQ(rec->stats().steps, static_cast<uint64_t>(steps));
  }
  const std::vector<char> wav = read_all(path);
  ASSERT_EQ(wav.size(), 44u + steps * 800 * 2);
  EXPECT_EQ(std::string(wav.data(), 4), "RIFF");
  EXPECT_EQ(std::string(wav.data() + 8, 8), "WAVEfmt ");
  uint32_t data_bytes = 0;
  std::memcpy(&data_bytes, wav.data() + 40, 4);
  EXPECT_EQ(data_bytes, steps * 800u * 2);
  // The same synthesiser, seed and cues, run here: the same samples.
  SoundSynth synth(s, 60, 77);
  std::vector<float> buf(SoundSynth::kMaxStepSamples);
  size_t at = 44, differ = 0;
  for (int i = 0; i < steps; ++i) {
    const int n = synth.render_step(cue_at(i), buf);
    for (int k = 0; k < n; ++k, at += 2) {
      int16_t v;
      std::memcpy(&v, wav.data() + at, 2);
      differ += v != static_cast<int16_t>(buf[static_cast<size_t>(k)] * 32767.0f);
    }
  }
  EXPECT_EQ(differ, 0u);
  std::remove(path.c_str());
}

// A headless render is reproducible: two recordings of the same cues match
// byte for byte.
TEST(SoundOutput, SameSeedSameRecording) {
  SoundSettings s;
  s.enabled = true;
  std::vector<char> files[2];
  for (int r = 0; r < 2; ++r) {
    const std::string path = temp_path(r ? "b.wav" : "a.wav");
    auto rec = open_sound_recording(s, 60, 5, path);
    for (int i = 0; i < 300; ++i) rec->push(cue_at(i));
    rec->finish();
    files[r] = read_all(path);
    std::remove(path.c_str());
  }
  ASSERT_GT(files[0].size(), 44u);
  EXPECT_EQ(files[0], files[1]);
}

TEST(SoundOutput, AlsaPlaysThroughTheFilePlugin) {
  const std::string raw = temp_path("played.raw");
  SoundSettings s;
  s.enabled = true;
  s.device = "file:FILE=" + raw + ",FORMAT=raw";
  SoundCue loud;
  loud.fire = Fixed::from_int(2);
  loud.activity = Fixed::from_int(1);
  uint64_t periods = 0;
  {
    auto out = open_sound_device(s, 60, 9);
    // The file plugin's slave is `null`, which takes periods as fast as
    // they come (it may have played silence before the first cue): play
    // 100 periods (2 s of sound) after the first cue is in.
    out->push(loud);
    const uint64_t from = out->stats().periods;
    while (out->stats().periods < from + 100) {
      out->push(loud);
      std::this_thread::yield();
    }
    EXPECT_TRUE(out->stats().device_open);
    out->finish();
    periods = out->stats().periods;
    EXPECT_EQ(out->stats().underruns, 0u);
  }
  const std::vector<char> played = read_all(raw);
  std::remove(raw.c_str());
  // Stereo S16 frames: every period that was written is in the file.
  const size_t frames = played.size() / 4;
  EXPECT_GE(frames, (periods - 1) * 960);
  EXPECT_LE(frames, periods * 960);
  size_t mismatched = 0;
  double energy = 0;
  const size_t last = frames - std::min<size_t>(frames, 80 * 960);  // the last 80 periods: the fire
  for (size_t f = 0; f < frames; ++f) {
    int16_t l, r;
    std::memcpy(&l, played.data() + f * 4, 2);
    std::memcpy(&r, played.data() + f * 4 + 2, 2);
    mismatched += l != r;
    if (f >= last) energy += static_cast<double>(l) * l;
  }
  EXPECT_EQ(mismatched, 0u) << "mono on both channels";
  // A fire of 2 at volume 0.6: clearly audible (above -40 dBFS RMS).
  EXPECT_GT(std::sqrt(energy / static_cast<double>(frames - last)) / 32768.0, 0.01);
}

// Issue 34: on a device that never blocks (ALSA's "null") the sound thread
// took periods as fast as it could render them, at 33 times a silent run's
// CPU. It now writes no further ahead of the wall clock than the buffer: over
// a measured half second, about 25 periods of 20 ms, not thousands.
TEST(SoundOutput, ADeviceThatNeverBlocksIsPacedByTheClock) {
  SoundSettings s;
  s.enabled = true;
  s.device = "null";
  auto out = open_sound_device(s, 60, 4);
  while (out->stats().periods < static_cast<uint64_t>(s.buffer_periods) + 2) out->push(cue_at(0));
  const auto t0 = std::chrono::steady_clock::now();
  const uint64_t p0 = out->stats().periods;
  poll(nullptr, 0, 500);  // a measuring window: the rate over time is what is measured
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const uint64_t periods = out->stats().periods - p0;
  out->finish();
  EXPECT_LE(static_cast<double>(periods), seconds / 0.020 + 2)
      << periods << " periods in " << seconds << " s";
  // And it still plays (at least half the real-time rate, even under qemu-user).
  EXPECT_GE(static_cast<double>(periods), seconds / 0.020 / 2) << periods << " periods";
}

TEST(SoundOutput, MissingDeviceIsLoggedAndNothingWaits) {
  SoundSettings s;
  s.enabled = true;
  s.device = "candela_no_such_pcm";
  ::testing::internal::CaptureStderr();
  auto out = open_sound_device(s, 60, 1);
  // A minute of cues from the frame loop: far more than the ring holds.
  for (int i = 0; i < 3600; ++i) out->push(cue_at(i));
  while (out->stats().open_attempts == 0) std::this_thread::yield();  // it has tried (and logged)
  out->finish();
  const std::string log = ::testing::internal::GetCapturedStderr();
  EXPECT_FALSE(out->stats().device_open);
  EXPECT_EQ(out->stats().periods, 0u);
  EXPECT_NE(log.find("sound: ALSA device \"candela_no_such_pcm\""), std::string::npos) << log;
  EXPECT_NE(log.find("without sound"), std::string::npos) << log;
}

TEST(SoundOutput, SoundPathBesideTheFrames) {
  EXPECT_EQ(sound_path_for("out/demo.mp4"), "out/demo.wav");
  EXPECT_EQ(sound_path_for("x.y4m"), "x.wav");
  EXPECT_EQ(sound_path_for("frames/"), "frames/sound.wav");
  EXPECT_EQ(sound_path_for("frames"), "frames/sound.wav");
}

}  // namespace
}  // namespace candela
