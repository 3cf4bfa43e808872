// The window's keys as wind events, the same road as every other input
// (InputHub::on_key queues them; drain() applies them): an arrow blows a gust
// from that side, space toward the viewer, `o` (Key::kBlowOut) blows the
// candles out.
#pragma once

#include <optional>

#include "display/display.h"
#include "wind/wind_field.h"

namespace candela {

// The wind event a key stands for; none for quit and other keys.
std::optional<WindEvent> key_wind_event(Key key, const WindSpec& wind);

}  // namespace candela
