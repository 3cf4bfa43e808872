#include "render.h"

#include <algorithm>
#include <cmath>

#include "model/colour_ramp.h"

namespace candela::tools {

Image gray_image(const float* gray, int width, int height) {
  Image img;
  img.width = width;
  img.height = height;
  img.channels = 1;
  img.pixels.resize(static_cast<size_t>(width) * height);
  for (size_t p = 0; p < img.pixels.size(); ++p)
    img.pixels[p] = static_cast<uint8_t>(std::lround(std::clamp(gray[p], 0.0f, 255.0f)));
  return img;
}

Image colourise(const float* gray, int width, int height, float hue_deg, float saturation,
                float glow_radius, float glow_strength, float black_level, float hue_top_deg) {
  const size_t n = static_cast<size_t>(width) * height;
  std::vector<float> rgb(3 * n);
  // The runtime's own ramp (model/colour_ramp.h), entry by rounded gray, as
  // the renderer's 8-bit target and ramp texture have it.
  const auto ramp = hls_ramp(hue_deg, saturation, black_level, hue_top_deg);
  for (size_t p = 0; p < n; ++p) {
    const auto i = static_cast<size_t>(std::lround(std::clamp(gray[p], 0.0f, 255.0f)));
    for (size_t c = 0; c < 3; ++c) rgb[3 * p + c] = ramp[4 * i + c] * (1.0f / 255.0f);
  }
  if (glow_strength > 0 && glow_radius > 0) {
    std::vector<float> glow = rgb;
    gaussian_blur(glow, width, height, 3, glow_radius * static_cast<float>(height));
    for (size_t i = 0; i < rgb.size(); ++i) rgb[i] += glow_strength * glow[i];
  }
  Image img;
  img.width = width;
  img.height = height;
  img.channels = 3;
  img.pixels.resize(3 * n);
  for (size_t i = 0; i < rgb.size(); ++i)
    img.pixels[i] = static_cast<uint8_t>(std::lround(255.0f * std::clamp(rgb[i], 0.0f, 1.0f)));
  return img;
}

Canvas::Canvas(int w, int h, std::array<uint8_t, 3> bg) {
  img.width = w;
  img.height = h;
  img.channels = 3;
  img.pixels.resize(static_cast<size_t>(w) * h * 3);
  for (size_t p = 0; p < img.pixels.size(); p += 3)
    for (int c = 0; c < 3; ++c) img.pixels[p + c] = bg[c];
}

void Canvas::dot(int x, int y, std::array<uint8_t, 3> c) {
  if (x < 0 || y < 0 || x >= img.width || y >= img.height) return;
  for (int k = 0; k < 3; ++k) img.row(y)[3 * x + k] = c[k];
}

void Canvas::line(double x0, double y0, double x1, double y1, std::array<uint8_t, 3> c) {
  const int n = static_cast<int>(std::ceil(std::max(std::abs(x1 - x0), std::abs(y1 - y0)))) + 1;
  for (int i = 0; i <= n; ++i) {
    const double t = static_cast<double>(i) / n;
    dot(static_cast<int>(std::lround(x0 + t * (x1 - x0))),
        static_cast<int>(std::lround(y0 + t * (y1 - y0))), c);
  }
}

void Canvas::rect(int x0, int y0, int x1, int y1, std::array<uint8_t, 3> c) {
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) dot(x, y, c);
}

std::array<uint8_t, 3> palette(int i) {
  static const std::array<uint8_t, 3> p[] = {{220, 50, 32},   {30, 120, 200}, {40, 160, 60},
                                             {230, 150, 0},   {140, 60, 170}, {0, 170, 170},
                                             {120, 120, 120}, {200, 80, 140}};
  return p[i % 8];
}

}  // namespace candela::tools
