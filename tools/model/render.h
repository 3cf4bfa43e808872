// Pictures made by the tools: a gray flame coloured in HLS (gray as
// lightness, chosen hue and saturation) with a glow, and the report plots.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "core/image.h"

namespace candela::tools {

// gray: display-encoded intensity 0..255, as datasets store it (values outside
// are clamped); values up to black_level become black and the rest are
// stretched back over 0..255, as the runtime's ramp does. Returns RGB.
Image colourise(const float* gray, int width, int height, float hue_deg, float saturation,
                float glow_radius, float glow_strength, float black_level = 0);
// Display-encoded 0..255 to an 8-bit gray image.
Image gray_image(const float* gray, int width, int height);

// A small RGB raster for plots.
struct Canvas {
  Image img;
  Canvas(int w, int h, std::array<uint8_t, 3> bg = {255, 255, 255});
  void dot(int x, int y, std::array<uint8_t, 3> c);
  void line(double x0, double y0, double x1, double y1, std::array<uint8_t, 3> c);
  void rect(int x0, int y0, int x1, int y1, std::array<uint8_t, 3> c);  // filled
};
// Distinct colours for clips / series.
std::array<uint8_t, 3> palette(int i);

}  // namespace candela::tools
