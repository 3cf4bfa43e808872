// What the scene sounds like in one animation step: a small, fixed-size
// summary the elements fill in (Element::add_sound_cue) and the synthesiser
// turns into that step's samples. Plain data: copied through a lock-free
// ring to the audio thread, never allocates.
#pragma once

#include <algorithm>
#include <cstdint>

#include "core/fixed.h"

namespace candela {

struct SoundCue {
  // How much fire burns, and how bright it is now: each fire element adds
  // its brightness (about 1 at its average light, 0.55..1.35 as it flickers).
  // The roar/hiss bed's level follows it.
  Fixed fire;
  // How lively the fire is (each fire element adds fire x liveliness, about
  // its fire share on average, more as its light flares): the crackle, pop
  // and knock rates are the [sound] rates times this.
  Fixed activity;
  // The strongest wind any element feels, m/s: a rise above the recent
  // level is a gust hitting, heard as a whoosh.
  Fixed wind;
  uint16_t blowouts = 0;  // candles that went out in this step (a puff each)
  uint16_t sputters = 0;  // candles whose flame clings to the wick in wind (they sputter)
  uint16_t lit = 0;       // candles alight
  // The master volume wanted now, 0..1 (the control socket's or MQTT's
  // `volume`, set by the frame loop); below 0: the [sound] table's volume.
  // The synthesiser glides to it (about 15 ms), so a change never clicks.
  float volume = -1.0f;

  // Folds a later step into this one (a backlog on the live audio thread):
  // events add up, levels are the latest.
  void merge_later(const SoundCue& later) {
    fire = later.fire;
    activity = later.activity;
    wind = later.wind;
    blowouts = static_cast<uint16_t>(std::min<int>(0xffff, blowouts + later.blowouts));
    sputters = later.sputters;
    lit = later.lit;
    volume = later.volume;
  }
};

}  // namespace candela
