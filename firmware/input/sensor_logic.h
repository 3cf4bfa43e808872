// From edges on a GPIO line to wind events, with no I/O: debounce, pulse-rate
// measurement and what each kind of sensor means for the wind. The GPIO
// source feeds it kernel edge timestamps; tests feed it synthetic timelines.
#pragma once

#include <array>
#include <cstdint>

#include "input/input_event.h"
#include "scene/input_spec.h"
#include "wind/wind_field.h"

namespace candela {

// Accepts a level once the line has stayed there for the debounce time, so a
// burst of edges shorter than that (contact bounce, a glitch) changes nothing
// unless it ends on the other level.
class Debouncer {
 public:
  explicit Debouncer(int64_t debounce_ns = 0, bool level = false)
      : debounce_ns_(debounce_ns), stable_(level), pending_(level) {}
  void reset(bool level) {
    stable_ = pending_ = level;
    has_pending_ = false;
  }
  void edge(bool level, int64_t t_ns);
  // True (with the new level and when its burst began) when a change settled by now.
  bool settle(int64_t now_ns, bool& level, int64_t& burst_start_ns);
  // When settle() next has something to decide; -1: nothing pending.
  int64_t deadline() const { return has_pending_ ? last_edge_ns_ + debounce_ns_ : -1; }
  bool level() const { return stable_; }

 private:
  int64_t debounce_ns_;
  bool stable_;
  bool pending_;
  bool has_pending_ = false;
  int64_t burst_start_ns_ = 0;
  int64_t last_edge_ns_ = 0;
};

// Pulses per second over a sliding window, from pulse timestamps: (n-1)
// intervals over the time they span, so the estimate does not depend on where
// the window's edges fall. Decays toward zero once pulses stop.
class PulseRateMeter {
 public:
  explicit PulseRateMeter(int64_t window_ns) : window_ns_(window_ns) {}
  void pulse(int64_t t_ns);
  double rate_hz(int64_t now_ns) const;
  void clear() { count_ = 0; }

 private:
  static constexpr size_t kMaxPulses = 1024;
  int64_t window_ns_;
  std::array<int64_t, kMaxPulses> times_{};
  size_t next_ = 0, count_ = 0;
};

// One GPIO sensor: its debouncer and what its settled levels mean.
class SensorLogic {
 public:
  // `base` is the scene's steady wind ([wind] speed and direction): a presence
  // sensor adds its draught to it; an anemometer replaces it.
  SensorLogic(const InputSpec& spec, uint16_t source, const WindSpec& wind);

  // The line's level when it was (re)opened; emits nothing.
  void start(bool level, int64_t now_ns);
  // An edge (kernel timestamp). Whatever had settled before it is applied first,
  // so edges read in one batch keep their own timing.
  void edge(bool active, int64_t t_ns, InputEventSink& sink);
  // Settles pending edges, updates the anemometer; returns the next deadline (-1: none).
  int64_t service(int64_t now_ns, InputEventSink& sink);
  // The line is gone: a presence draught or anemometer wind must not stay on.
  void lost(int64_t now_ns, InputEventSink& sink);

  uint64_t activations() const { return activations_; }
  double speed() const { return speed_; }

 private:
  void on_level(bool active, int64_t t_ns, InputEventSink& sink);
  void emit(WindEvent::Type type, Fixed x, Fixed z, int64_t t_ns, InputEventSink& sink);

  InputSpec::Kind kind_;
  uint16_t source_;
  Fixed dir_x_, dir_z_, strength_;
  Fixed base_x_, base_z_;
  double calibration_;
  Debouncer debouncer_;
  PulseRateMeter meter_;
  bool present_ = false;
  double speed_ = 0;  // anemometer m/s last emitted
  uint64_t activations_ = 0;
};

}  // namespace candela
