// Headless: each cue becomes one step of samples, written to a .wav.
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

#include "core/error.h"
#include "core/log.h"
#include "sound/cue_ring.h"
#include "sound/sound_output.h"
#include "sound/sound_synth.h"
#include "sound/wav_file.h"

namespace candela {
namespace {

bool ends_with(const std::string& s, const char* suffix) {
  const std::string t(suffix);
  return s.size() >= t.size() && s.compare(s.size() - t.size(), t.size(), t) == 0;
}

class SoundRecording final : public SoundOutput {
 public:
  SoundRecording(const SoundSettings& s, int sps, uint64_t seed, const std::string& path)
      : synth_(s, sps, seed),
        wav_(path, SoundSynth::kSampleRate, 1),
        samples_(SoundSynth::kMaxStepSamples),
        pcm_(SoundSynth::kMaxStepSamples) {
    thread_ = std::thread([this] { run(); });
  }
  ~SoundRecording() override {
    try {
      finish();
    } catch (const std::exception& e) {
      LOG_ERROR("%s", e.what());
    }
  }
  void push(const SoundCue& cue) override { ring_.push(cue); }
  void finish() override {
    if (finished_) return;
    finished_ = true;
    ring_.close();
    if (thread_.joinable()) thread_.join();
    if (error_) std::rethrow_exception(error_);
    wav_.close();
  }
  SoundStats stats() const override {
    SoundStats st;
    st.steps = steps_.load(std::memory_order_relaxed);
    st.frames = frames_.load(std::memory_order_relaxed);
    return st;
  }

 private:
  void run() {
    SoundCue cue;
    const uint64_t max_frames = uint64_t{kMaxRecordSeconds} * SoundSynth::kSampleRate;
    bool capped = false;
    while (ring_.pop(cue)) {
      if (error_ || capped) continue;  // keep draining: push() must never wait forever
      try {
        const int n = synth_.render_step(cue, samples_);
        for (int i = 0; i < n; ++i)
          pcm_[static_cast<size_t>(i)] =
              static_cast<int16_t>(samples_[static_cast<size_t>(i)] * 32767.0f);
        wav_.write(pcm_.data(), static_cast<size_t>(n));
        steps_.store(synth_.steps(), std::memory_order_relaxed);
        frames_.store(wav_.frames(), std::memory_order_relaxed);
        if (wav_.frames() >= max_frames) {
          capped = true;
          LOG_WARN("%s: the recording's sound ends after %d hours (the limit)", wav_.path().c_str(),
                   kMaxRecordSeconds / 3600);
        }
      } catch (...) {
        error_ = std::current_exception();
      }
    }
  }

  SoundSynth synth_;
  WavFile wav_;
  std::vector<float> samples_;
  std::vector<int16_t> pcm_;
  CueRing ring_;
  std::atomic<uint64_t> steps_{0}, frames_{0};
  std::exception_ptr error_;  // written by the thread, read after join
  bool finished_ = false;
  std::thread thread_;
};

}  // namespace

std::string sound_path_for(const std::string& out) {
  for (const char* ext : {".y4m", ".mp4", ".mkv", ".webm"})
    if (ends_with(out, ext)) return out.substr(0, out.size() - std::string(ext).size()) + ".wav";
  std::string dir = out;
  while (dir.size() > 1 && dir.back() == '/') dir.pop_back();
  return dir + "/sound.wav";
}

std::unique_ptr<SoundOutput> open_sound_recording(const SoundSettings& s, int sps, uint64_t seed,
                                                  const std::string& path) {
  return std::make_unique<SoundRecording>(s, sps, seed, path);
}

}  // namespace candela
