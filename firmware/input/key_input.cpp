#include "input/key_input.h"

namespace candela {

std::optional<WindEvent> key_wind_event(Key key, const WindSpec& wind) {
  const Fixed g = wind.gust_speed;
  switch (key) {
    case Key::kLeft:  // from the left: blows right
      return WindEvent{WindEvent::Type::kGust, g, {}};
    case Key::kRight:
      return WindEvent{WindEvent::Type::kGust, -g, {}};
    case Key::kUp:  // from behind the candles: toward the viewer
      return WindEvent{WindEvent::Type::kGust, {}, g};
    case Key::kDown:
      return WindEvent{WindEvent::Type::kGust, {}, -g};
    case Key::kSpace:  // toward the viewer
      return WindEvent{WindEvent::Type::kGust, {}, g};
    case Key::kBlowOut:  // someone blowing from the front-left
      return WindEvent{WindEvent::Type::kBlowOut, wind.blowout_speed * Fixed::from_ratio(3, 5),
                       -wind.blowout_speed * Fixed::from_ratio(4, 5)};
    case Key::kQuit:
    case Key::kOther:
      break;
  }
  return std::nullopt;
}

}  // namespace candela
