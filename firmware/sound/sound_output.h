// Where the scene's sound goes: the frame loop hands each animation step's
// SoundCue to push(); an audio thread of the output's own turns cues into
// samples (SoundSynth) and plays them (ALSA) or writes them (.wav).
//
// The handoff is a lock-free ring (cue_ring.h). Live (ALSA): push() never
// waits; the audio thread renders one step per cue as the device asks for
// 20 ms periods, holding the last levels when the frame loop is late and
// folding a backlog of cues together when it is early. Recording: every cue
// becomes exactly one step of samples (deterministic; push() waits only if
// the writer is 256 steps behind, as a frame writer waits for the disk).
// Neither thread allocates once running.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <string>

#include "sound/sound_cue.h"
#include "sound/sound_settings.h"

namespace candela {

struct SoundStats {
  uint64_t steps = 0;          // steps rendered
  uint64_t periods = 0;        // live: 20 ms periods written to the device
  uint64_t underruns = 0;      // live: times the device ran dry (recovered)
  uint64_t frames = 0;         // recording: sample frames written
  uint64_t open_attempts = 0;  // live: times the device was tried
  bool device_open = false;
};

class SoundOutput {
 public:
  virtual ~SoundOutput() = default;
  // One animation step's cue, from the frame loop. Never allocates.
  virtual void push(const SoundCue& cue) = 0;
  // Stops the audio thread; a recording writes its file's end. Throws
  // RuntimeError if the recording could not be written (live trouble is only logged).
  virtual void finish() = 0;
  virtual SoundStats stats() const = 0;
};

// The audio recorded beside headless output: "DIR/" (PNG folder) ->
// DIR/sound.wav, "x.y4m" / "x.mp4" / "x.mkv" / "x.webm" -> x.wav.
std::string sound_path_for(const std::string& out_path);

// Writes a .wav (mono, 16-bit, 48 kHz). At most kMaxRecordSeconds of sound
// are written (then the file ends and a warning is logged once).
inline constexpr int kMaxRecordSeconds = 4 * 3600;
std::unique_ptr<SoundOutput> open_sound_recording(const SoundSettings& settings,
                                                  int steps_per_second, uint64_t seed,
                                                  const std::string& wav_path);

// Plays through ALSA on settings.device (48 kHz, S16, 20 ms periods,
// settings.buffer_periods of them). A device that cannot be opened or fails
// is logged and retried every 2 s; the display runs on meanwhile.
std::unique_ptr<SoundOutput> open_sound_device(const SoundSettings& settings, int steps_per_second,
                                               uint64_t seed);

}  // namespace candela
