// Pictures made by the tools: a gray flame coloured as the runtime colours it
// (the HLS ramp of model/colour_ramp.h) with a glow, and the report plots.
#pragma once

#include <array>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "core/image.h"

namespace candela::tools {

// gray: display-encoded intensity 0..255, as datasets store it (values outside
// are clamped), coloured through the runtime's HLS ramp (hls_ramp: luma kept,
// values up to black_level black, the hue moving to hue_top_deg as the gray
// nears white; NaN: one hue), then the glow added. Returns RGB.
Image colourise(const float* gray, int width, int height, float hue_deg, float saturation,
                float glow_radius, float glow_strength, float black_level = 0,
                float hue_top_deg = std::numeric_limits<float>::quiet_NaN());
// Display-encoded 0..255 to an 8-bit gray image.
Image gray_image(const float* gray, int width, int height);
// A gray frame scaled (bilinear) to fit inside out_width x out_height, its
// aspect kept, centred on black (0): a 128x160 model frame at 1280x720 is a
// 576x720 flame in the middle. Rows top-down, as the input.
std::vector<float> fit_gray(const float* gray, int width, int height, int out_width,
                            int out_height);

// A small RGB raster for plots.
struct Canvas {
  Image img;
  Canvas(int w, int h, std::array<uint8_t, 3> bg = {255, 255, 255});
  void dot(int x, int y, std::array<uint8_t, 3> c);
  void line(double x0, double y0, double x1, double y1, std::array<uint8_t, 3> c);
  void rect(int x0, int y0, int x1, int y1, std::array<uint8_t, 3> c);  // filled
  // Text in a 5x7 bitmap font (A-Z, 0-9 and - . , ( ) / : _ + = %; lower
  // case drawn as upper case, anything else as '?'), `scale` pixels a font
  // pixel, top-left at (x, y). Returns its width.
  int text(int x, int y, std::string_view s, std::array<uint8_t, 3> c, int scale = 1);
  // Text turned a quarter anticlockwise (reading bottom to top), its
  // bottom-left at (x, y): a vertical axis's title.
  void text_up(int x, int y, std::string_view s, std::array<uint8_t, 3> c, int scale = 1);
  static int text_width(std::string_view s, int scale = 1) {
    return s.empty() ? 0 : (6 * static_cast<int>(s.size()) - 1) * scale;
  }
  static constexpr int kTextHeight = 7;  // font pixels
};
// Distinct colours for clips / series.
std::array<uint8_t, 3> palette(int i);

}  // namespace candela::tools
