// The fire's events: crackles (a burst of 1..5 sharp clicks, 1.5..7 kHz),
// pops (one louder, lower crack), and knocks (a settling log: a hollow
// thud, 70..160 Hz, ringing ~0.2 s). Each kind happens as a Poisson process
// (event_clock.h) at its [sound] rate times the fire's activity.
#pragma once

#include <cstdint>

#include "core/fixed.h"
#include "sound/event_clock.h"
#include "sound/impulse_voice.h"

namespace candela {

class FireEvents {
 public:
  FireEvents(uint64_t seed, Fixed crackle_rate, Fixed pop_rate, Fixed knock_rate, float level);
  // Schedules this step's events (`n` samples) into `voices`.
  void step(Fixed activity, int n, ImpulseVoices& voices);
  uint64_t crackles() const { return crackles_; }  // events so far, for tests
  uint64_t pops() const { return pops_; }
  uint64_t knocks() const { return knocks_; }

 private:
  float uniform();  // 0..1, from the shape generator
  EventClock crackle_clock_, pop_clock_, knock_clock_;
  Fixed crackle_rate_, pop_rate_, knock_rate_;
  Pcg32 shape_rng_;
  float level_;
  uint64_t crackles_ = 0, pops_ = 0, knocks_ = 0;
};

}  // namespace candela
