#include "core/wxh.h"

#include <cstdint>

namespace candela {
namespace {
// Plain digits within [lo, hi]; false for anything else.
bool parse_bounded(std::string_view s, int lo, int hi, int* out) {
  if (s.empty()) return false;
  int64_t v = 0;
  for (char c : s) {
    if (c < '0' || c > '9') return false;
    v = v * 10 + (c - '0');
    if (v > hi) return false;
  }
  if (v < lo) return false;
  *out = static_cast<int>(v);
  return true;
}
}  // namespace

std::optional<WxH> parse_wxh(std::string_view text, WxH min, WxH max) {
  const size_t x = text.find('x');
  if (x == std::string_view::npos) return std::nullopt;
  WxH s;
  if (!parse_bounded(text.substr(0, x), min.width, max.width, &s.width) ||
      !parse_bounded(text.substr(x + 1), min.height, max.height, &s.height))
    return std::nullopt;
  return s;
}

}  // namespace candela
