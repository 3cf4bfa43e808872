// What an input thread hands the frame loop: a wind event, and when its
// cause happened (CLOCK_MONOTONIC ns) so the loop can measure input latency.
#pragma once

#include <cstdint>

#include "wind/wind_field.h"

namespace candela {

struct InputEvent {
  WindEvent wind;
  int64_t cause_ns = 0;
  uint16_t source = 0;  // index of the InputSpec; kControlSource or kKeySource
};
inline constexpr uint16_t kControlSource = 0xFFFF;  // the control socket and MQTT
inline constexpr uint16_t kKeySource = 0xFFFE;      // the display's keys (InputHub::on_key)

// Where sensor logic puts its events (the hub's queue, or a test's vector).
class InputEventSink {
 public:
  virtual ~InputEventSink() = default;
  virtual void emit(const InputEvent& event) = 0;
};

int64_t monotonic_ns();

}  // namespace candela
