// The scene's [sound] table (README "Sound"), validated by parse_sound().
#pragma once

#include <cstdint>
#include <string>

#include "core/fixed.h"

namespace candela {

class ParamReader;

struct SoundSettings {
  bool enabled = false;  // true once the scene has a [sound] table (enabled = true by default)
  float volume = 0.6f;   // master gain, 0..1
  std::string device = "default";  // ALSA PCM name: "default", "hw:1,0", "plughw:CARD=vc4hdmi0"...
  Fixed crackle_rate = Fixed::from_int(6);      // crackles per second at activity 1
  Fixed pop_rate = Fixed::from_ratio(3, 10);    // pops per second at activity 1
  Fixed knock_rate = Fixed::from_ratio(1, 30);  // settling-log knocks per second at activity 1
  Fixed sputter_rate = Fixed::from_int(3);      // sputters per second per sputtering candle
  float roar = 1.0f;                            // level of the roar/hiss bed, 0..4
  float crackle = 1.0f;                         // level of crackles, pops and knocks, 0..4
  float whoosh = 1.0f;                          // level of the gust whoosh, 0..4
  float candle = 1.0f;                          // level of candle sputters and puffs, 0..4
  int buffer_periods = 3;  // ALSA buffer, in 20 ms periods (latency vs underruns)
  uint64_t seed = 0;       // 0: from the scene's seed
};

// Reads [sound]; `present`: the scene has the table (without it sound is
// off). Calls reader.finish().
SoundSettings parse_sound(ParamReader& reader, bool present);

}  // namespace candela
