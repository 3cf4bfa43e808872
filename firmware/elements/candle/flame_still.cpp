#include "elements/candle/flame_still.h"

#include <algorithm>
#include <cmath>

namespace candela {
namespace {

double smoothstep(double e0, double e1, double x) {
  const double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
  return t * t * (3 - 2 * t);
}
double mix(double a, double b, double t) { return a + (b - a) * t; }

}  // namespace

Image make_flame_still(int height, const StillLayout& layout) {
  Image img;
  img.height = height;
  img.width = height / 2;
  img.channels = 4;
  img.pixels.assign(static_cast<size_t>(img.width) * img.height * 4, 0);
  const double aspect = static_cast<double>(img.width) / img.height;
  const double base = layout.base.to_double(), tip = layout.tip.to_double() + 0.04;
  // Widest (at 3/8 of the height) where the control lines V1, V2 sit.
  const double max_half = layout.half_width.to_double() * 1.15;
  for (int py = 0; py < img.height; ++py) {
    uint8_t* row = img.row(py);
    for (int px = 0; px < img.width; ++px) {
      const double x = ((px + 0.5) / img.width - 0.5) * aspect;
      const double y = 1.0 - (py + 0.5) / img.height;
      // Height along the flame: 0 at the base, 1 at the tip; a little below
      // the base the bottom rounds off.
      const double t = (y - base) / (tip - base);
      if (t < -0.08 || t > 1) continue;
      const double tt = std::max(t + 0.08, 0.0) / 1.08;
      const double half = max_half * std::pow(tt, 0.45) * std::pow(1 - tt, 0.8) / 0.455;
      if (half <= 1e-6) continue;
      const double d = std::abs(x) / half;  // 0 on the axis, 1 at the edge
      if (d >= 1) continue;
      // Colours: a thin orange rim, a yellow body, a large core bright enough
      // to clip to white (as a camera sees a candle), the blue base at the wick.
      double r = 1.0, g = 0.55, b = 0.16;
      const double body = smoothstep(0.98, 0.8, d);
      r = mix(r, 1.0, body), g = mix(g, 0.86, body), b = mix(b, 0.5, body);
      const double core =
          smoothstep(0.82, 0.35, d) * smoothstep(0.1, 0.3, t) * smoothstep(0.97, 0.6, t);
      r = mix(r, 1.0, core), g = mix(g, 1.0, core), b = mix(b, 0.97, core);
      const double blue = smoothstep(0.24, 0.04, t) * smoothstep(0.1, 0.55, d + 0.3 * (0.24 - t));
      r = mix(r, 0.2, blue), g = mix(g, 0.3, blue), b = mix(b, 0.95, blue);
      // A crisp edge (a real flame's luminous zone ends sharply) and a pointed
      // tip; the blue base is fainter and the root, below the wick top, fades.
      double a = smoothstep(1.0, 0.9, d) * smoothstep(1.0, 0.93, t);
      a *= 1 - 0.55 * blue;
      a *= 0.55 + 0.45 * smoothstep(-0.08, 0.04, t);
      uint8_t* p = row + px * 4;
      p[0] = static_cast<uint8_t>(std::lround(std::clamp(r, 0.0, 1.0) * 255));
      p[1] = static_cast<uint8_t>(std::lround(std::clamp(g, 0.0, 1.0) * 255));
      p[2] = static_cast<uint8_t>(std::lround(std::clamp(b, 0.0, 1.0) * 255));
      p[3] = static_cast<uint8_t>(std::lround(std::clamp(a, 0.0, 1.0) * 255));
    }
  }
  return img;
}

}  // namespace candela
