// Live sound through ALSA, on its own thread. The thread asks the synth for
// one step per cue as the device takes 20 ms periods (blocking writes pace
// it); nothing here allocates once the device is open.
#include <alsa/asoundlib.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <condition_variable>
#include <cstdarg>
#include <cstdio>
#include <mutex>
#include <thread>
#include <vector>

#include "core/log.h"
#include "sound/cue_ring.h"
#include "sound/sound_output.h"
#include "sound/sound_synth.h"

namespace candela {
namespace {

constexpr int kPeriodFrames = SoundSynth::kSampleRate / 50;  // 20 ms
constexpr int kMaxChannels = 8;
constexpr uint32_t kMaxBacklog = 2;  // cues waiting beyond this are folded in (latency bound)

// libasound prints its own errors to stderr (8 lines for a missing card, at
// every 2 s retry): they go to the debug log; our one line says what failed.
void alsa_message(const char* file, int line, const char* function, int err, const char* fmt, ...) {
  if (log_level() > LogLevel::kDebug) return;
  char text[256];
  va_list ap;
  va_start(ap, fmt);
  std::vsnprintf(text, sizeof text, fmt, ap);
  va_end(ap);
  LOG_DEBUG("ALSA lib %s:%d (%s): %s%s%s", file, line, function, text, err ? ": " : "",
            err ? snd_strerror(err) : "");
}

class AlsaOutput final : public SoundOutput {
 public:
  AlsaOutput(const SoundSettings& s, int sps, uint64_t seed)
      : settings_(s),
        synth_(s, sps, seed),
        step_(SoundSynth::kMaxStepSamples),
        period_(static_cast<size_t>(kPeriodFrames) * kMaxChannels) {
    snd_lib_error_set_handler(alsa_message);
    thread_ = std::thread([this] { run(); });
  }
  ~AlsaOutput() override { finish(); }

  void push(const SoundCue& cue) override {
    // Never waits: a full ring (the device stalled) folds cues into one
    // pending cue, so a blow-out is not lost.
    if (has_pending_) {
      pending_.merge_later(cue);
      if (ring_.try_push(pending_)) has_pending_ = false;
    } else if (!ring_.try_push(cue)) {
      pending_ = cue;
      has_pending_ = true;
    }
  }
  void finish() override {
    {
      std::lock_guard lock(mu_);  // so the retry wait cannot miss it
      if (stop_.exchange(true)) return;
    }
    cv_.notify_all();
    ring_.close();
    if (thread_.joinable()) thread_.join();
  }
  SoundStats stats() const override {
    SoundStats st;
    st.steps = steps_.load(std::memory_order_relaxed);
    st.periods = periods_.load(std::memory_order_relaxed);
    st.underruns = underruns_.load(std::memory_order_relaxed);
    st.device_open = open_.load(std::memory_order_relaxed);
    st.open_attempts = attempts_.load(std::memory_order_acquire);
    return st;
  }

 private:
  bool stopping() const { return stop_.load(std::memory_order_acquire); }

  // Opens and configures the device; logs why not (once per outage).
  bool open_device() {
    snd_pcm_t* pcm = nullptr;
    const char* dev = settings_.device.c_str();
    int rc = snd_pcm_open(&pcm, dev, SND_PCM_STREAM_PLAYBACK, 0);
    const char* what = "cannot open it";
    if (rc >= 0) {
      snd_pcm_hw_params_t* hw;
      snd_pcm_hw_params_alloca(&hw);
      unsigned rate = SoundSynth::kSampleRate, channels = 2;
      snd_pcm_uframes_t period = kPeriodFrames,
                        buffer = static_cast<snd_pcm_uframes_t>(kPeriodFrames) *
                                 static_cast<unsigned>(settings_.buffer_periods);
      int dir = 0;
      what = "it refuses 48 kHz 16-bit interleaved playback";
      if ((rc = snd_pcm_hw_params_any(pcm, hw)) >= 0 &&
          (rc = snd_pcm_hw_params_set_access(pcm, hw, SND_PCM_ACCESS_RW_INTERLEAVED)) >= 0 &&
          (rc = snd_pcm_hw_params_set_format(pcm, hw, SND_PCM_FORMAT_S16_LE)) >= 0 &&
          (rc = snd_pcm_hw_params_set_channels_near(pcm, hw, &channels)) >= 0 &&
          (rc = snd_pcm_hw_params_set_rate(pcm, hw, rate, 0)) >= 0 &&
          (rc = snd_pcm_hw_params_set_period_size_near(pcm, hw, &period, &dir)) >= 0 &&
          (rc = snd_pcm_hw_params_set_buffer_size_near(pcm, hw, &buffer)) >= 0 &&
          (rc = snd_pcm_hw_params(pcm, hw)) >= 0) {
        if (channels < 1 || channels > kMaxChannels) {
          rc = -EINVAL;
          what = "it offers no 1..8 channel layout";
        }
      }
      if (rc >= 0) {
        snd_pcm_sw_params_t* sw;
        snd_pcm_sw_params_alloca(&sw);
        what = "it refuses the software parameters";
        if ((rc = snd_pcm_sw_params_current(pcm, sw)) >= 0 &&
            (rc = snd_pcm_sw_params_set_start_threshold(pcm, sw, buffer - period)) >= 0 &&
            (rc = snd_pcm_sw_params_set_avail_min(pcm, sw, period)) >= 0)
          rc = snd_pcm_sw_params(pcm, sw);
      }
      if (rc >= 0) {
        pcm_ = pcm;
        channels_ = static_cast<int>(channels);
        if (reported_)
          LOG_INFO("sound: ALSA device \"%s\" is back", dev);
        else
          LOG_INFO("sound: ALSA \"%s\", %u channel(s), 48 kHz, period %lu, buffer %lu frames", dev,
                   channels, static_cast<unsigned long>(period),
                   static_cast<unsigned long>(buffer));
        reported_ = false;
        open_.store(true, std::memory_order_relaxed);
        attempts_.fetch_add(1, std::memory_order_release);
        return true;
      }
      snd_pcm_close(pcm);
    }
    if (!reported_)
      LOG_WARN(
          "sound: ALSA device \"%s\": %s (%s); the display runs on without sound, retrying "
          "every 2 s",
          dev, what, snd_strerror(rc));
    reported_ = true;
    attempts_.fetch_add(1, std::memory_order_release);  // after the log line
    return false;
  }

  void close_device() {
    if (pcm_) {
      snd_pcm_drop(pcm_);
      snd_pcm_close(pcm_);
    }
    pcm_ = nullptr;
    open_.store(false, std::memory_order_relaxed);
  }

  // The cue for the next step: the next one queued (a backlog folded in),
  // or, if the frame loop is late, the last levels again without its events.
  SoundCue next_cue() {
    SoundCue cue;
    if (ring_.try_pop(cue)) {
      SoundCue later;
      while (ring_.size() > kMaxBacklog && ring_.try_pop(later)) cue.merge_later(later);
      held_ = cue;
      held_.blowouts = 0;
      return cue;
    }
    return held_;
  }

  void fill_period() {
    for (int i = 0; i < kPeriodFrames; ++i) {
      if (step_pos_ == step_len_) {
        step_len_ = synth_.render_step(next_cue(), step_);
        step_pos_ = 0;
        steps_.store(synth_.steps(), std::memory_order_relaxed);
      }
      const auto v = static_cast<int16_t>(step_[static_cast<size_t>(step_pos_++)] * 32767.0f);
      for (int c = 0; c < channels_; ++c) period_[static_cast<size_t>(i * channels_ + c)] = v;
    }
  }

  void run() {
    while (!stopping()) {
      if (!pcm_ && !open_device()) {
        SoundCue dropped;
        while (ring_.try_pop(dropped)) held_ = dropped;  // no device: keep the ring empty
        std::unique_lock lock(mu_);
        cv_.wait_for(lock, std::chrono::seconds(2), [&] { return stopping(); });
        continue;
      }
      fill_period();
      const auto write_start = std::chrono::steady_clock::now();
      snd_pcm_sframes_t done = 0;
      while (done < kPeriodFrames) {
        snd_pcm_sframes_t n = snd_pcm_writei(
            pcm_, period_.data() + static_cast<size_t>(done) * static_cast<size_t>(channels_),
            static_cast<snd_pcm_uframes_t>(kPeriodFrames - done));
        if (n == -EPIPE) underruns_.fetch_add(1, std::memory_order_relaxed);
        if (n < 0) n = snd_pcm_recover(pcm_, static_cast<int>(n), 1);
        if (n < 0) {
          LOG_WARN("sound: ALSA device \"%s\" failed (%s); retrying every 2 s",
                   settings_.device.c_str(), snd_strerror(static_cast<int>(n)));
          reported_ = true;
          close_device();
          break;
        }
        done += n;
      }
      if (pcm_) {
        periods_.fetch_add(1, std::memory_order_relaxed);
        pace(write_start);
      } else {
        paced_ = 0;
      }
    }
    close_device();
  }

  // A device that never blocks (ALSA's "null", a plugin that writes a file)
  // took periods as fast as they were rendered: the thread spun at 33 times
  // a silent run's CPU (issue 34). No period goes out more than the buffer
  // ahead of the wall clock. A device that blocked on this write keeps time
  // itself: the clock is set to it, so its drift never makes this wait.
  void pace(std::chrono::steady_clock::time_point write_start) {
    using namespace std::chrono;
    constexpr auto kPeriod = microseconds(1'000'000LL * kPeriodFrames / SoundSynth::kSampleRate);
    const auto now = steady_clock::now();
    if (paced_ == 0 || now - write_start > kPeriod / 4) {
      paced_ = 1;
      pace_origin_ = now;
      return;
    }
    const auto due = pace_origin_ + kPeriod * (paced_++ - settings_.buffer_periods);
    if (due <= now) return;
    std::unique_lock lock(mu_);
    cv_.wait_until(lock, due, [&] { return stopping(); });
  }

  SoundSettings settings_;
  SoundSynth synth_;
  std::vector<float> step_;
  std::vector<int16_t> period_;
  int step_pos_ = 0, step_len_ = 0;
  int channels_ = 2;
  snd_pcm_t* pcm_ = nullptr;
  bool reported_ = false;
  int64_t paced_ = 0;  // periods since pace_origin_ (0: not pacing yet)
  std::chrono::steady_clock::time_point pace_origin_;
  SoundCue held_;
  // Producer side (the frame loop) only.
  SoundCue pending_;
  bool has_pending_ = false;
  CueRing ring_;
  std::atomic<uint64_t> steps_{0}, periods_{0}, underruns_{0};
  std::atomic<bool> open_{false};
  std::atomic<uint64_t> attempts_{0};
  std::atomic<bool> stop_{false};
  std::mutex mu_;  // the 2 s retry wait and pace()'s (a device that does not block) only
  std::condition_variable cv_;
  std::thread thread_;
};

}  // namespace

std::unique_ptr<SoundOutput> open_sound_device(const SoundSettings& s, int sps, uint64_t seed) {
  return std::make_unique<AlsaOutput>(s, sps, seed);
}

}  // namespace candela
