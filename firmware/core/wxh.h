// "WxH" sizes on command lines: candela --size, candela-record --size and
// --preview-size, candela-tool studio --size, the fluid tools' --grid and
// --size. One parser; each caller says its bounds and words its own error.
#pragma once

#include <optional>
#include <string_view>

namespace candela {

struct WxH {
  int width = 0, height = 0;
};

// Two whole numbers in plain digits joined by 'x' (e.g. "1280x720"), the
// width within [min.width, max.width] and the height within [min.height,
// max.height]; nullopt for anything else (signs, spaces, trailing text).
std::optional<WxH> parse_wxh(std::string_view text, WxH min, WxH max);

}  // namespace candela
