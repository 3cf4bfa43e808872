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

std::vector<float> fit_gray(const float* gray, int width, int height, int out_width,
                            int out_height) {
  std::vector<float> out(static_cast<size_t>(out_width) * out_height, 0.0f);
  const double scale =
      std::min(static_cast<double>(out_width) / width, static_cast<double>(out_height) / height);
  const int fit_w = std::max(1, static_cast<int>(std::lround(width * scale)));
  const int fit_h = std::max(1, static_cast<int>(std::lround(height * scale)));
  const int x0 = (out_width - fit_w) / 2, y0 = (out_height - fit_h) / 2;
  auto at = [&](int x, int y) {
    return gray[static_cast<size_t>(std::clamp(y, 0, height - 1)) * width +
                std::clamp(x, 0, width - 1)];
  };
  for (int y = 0; y < fit_h; ++y) {
    // Pixel centres mapped onto the source's (edges clamped).
    const double sy = (y + 0.5) * height / fit_h - 0.5;
    const int iy = static_cast<int>(std::floor(sy));
    const float fy = static_cast<float>(sy - iy);
    float* row = out.data() + static_cast<size_t>(y0 + y) * out_width + x0;
    for (int x = 0; x < fit_w; ++x) {
      const double sx = (x + 0.5) * width / fit_w - 0.5;
      const int ix = static_cast<int>(std::floor(sx));
      const float fx = static_cast<float>(sx - ix);
      const float top = at(ix, iy) + fx * (at(ix + 1, iy) - at(ix, iy));
      const float bottom = at(ix, iy + 1) + fx * (at(ix + 1, iy + 1) - at(ix, iy + 1));
      row[x] = top + fy * (bottom - top);
    }
  }
  return out;
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

namespace {

// The 5x7 font: seven rows of five bits (bit 4 the leftmost column).
struct Glyph {
  char c;
  std::array<uint8_t, 7> rows;
};
constexpr Glyph kFont[] = {
    {'A', {0x0e, 0x11, 0x11, 0x1f, 0x11, 0x11, 0x11}},
    {'B', {0x1e, 0x11, 0x11, 0x1e, 0x11, 0x11, 0x1e}},
    {'C', {0x0e, 0x11, 0x10, 0x10, 0x10, 0x11, 0x0e}},
    {'D', {0x1e, 0x11, 0x11, 0x11, 0x11, 0x11, 0x1e}},
    {'E', {0x1f, 0x10, 0x10, 0x1e, 0x10, 0x10, 0x1f}},
    {'F', {0x1f, 0x10, 0x10, 0x1e, 0x10, 0x10, 0x10}},
    {'G', {0x0e, 0x11, 0x10, 0x17, 0x11, 0x11, 0x0f}},
    {'H', {0x11, 0x11, 0x11, 0x1f, 0x11, 0x11, 0x11}},
    {'I', {0x0e, 0x04, 0x04, 0x04, 0x04, 0x04, 0x0e}},
    {'J', {0x07, 0x02, 0x02, 0x02, 0x02, 0x12, 0x0c}},
    {'K', {0x11, 0x12, 0x14, 0x18, 0x14, 0x12, 0x11}},
    {'L', {0x10, 0x10, 0x10, 0x10, 0x10, 0x10, 0x1f}},
    {'M', {0x11, 0x1b, 0x15, 0x15, 0x11, 0x11, 0x11}},
    {'N', {0x11, 0x11, 0x19, 0x15, 0x13, 0x11, 0x11}},
    {'O', {0x0e, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0e}},
    {'P', {0x1e, 0x11, 0x11, 0x1e, 0x10, 0x10, 0x10}},
    {'Q', {0x0e, 0x11, 0x11, 0x11, 0x15, 0x12, 0x0d}},
    {'R', {0x1e, 0x11, 0x11, 0x1e, 0x14, 0x12, 0x11}},
    {'S', {0x0f, 0x10, 0x10, 0x0e, 0x01, 0x01, 0x1e}},
    {'T', {0x1f, 0x04, 0x04, 0x04, 0x04, 0x04, 0x04}},
    {'U', {0x11, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0e}},
    {'V', {0x11, 0x11, 0x11, 0x11, 0x11, 0x0a, 0x04}},
    {'W', {0x11, 0x11, 0x11, 0x15, 0x15, 0x15, 0x0a}},
    {'X', {0x11, 0x11, 0x0a, 0x04, 0x0a, 0x11, 0x11}},
    {'Y', {0x11, 0x11, 0x0a, 0x04, 0x04, 0x04, 0x04}},
    {'Z', {0x1f, 0x01, 0x02, 0x04, 0x08, 0x10, 0x1f}},
    {'0', {0x0e, 0x11, 0x13, 0x15, 0x19, 0x11, 0x0e}},
    {'1', {0x04, 0x0c, 0x04, 0x04, 0x04, 0x04, 0x0e}},
    {'2', {0x0e, 0x11, 0x01, 0x02, 0x04, 0x08, 0x1f}},
    {'3', {0x1f, 0x02, 0x04, 0x02, 0x01, 0x11, 0x0e}},
    {'4', {0x02, 0x06, 0x0a, 0x12, 0x1f, 0x02, 0x02}},
    {'5', {0x1f, 0x10, 0x1e, 0x01, 0x01, 0x11, 0x0e}},
    {'6', {0x06, 0x08, 0x10, 0x1e, 0x11, 0x11, 0x0e}},
    {'7', {0x1f, 0x01, 0x02, 0x04, 0x08, 0x08, 0x08}},
    {'8', {0x0e, 0x11, 0x11, 0x0e, 0x11, 0x11, 0x0e}},
    {'9', {0x0e, 0x11, 0x11, 0x0f, 0x01, 0x02, 0x0c}},
    {'-', {0x00, 0x00, 0x00, 0x1f, 0x00, 0x00, 0x00}},
    {'.', {0x00, 0x00, 0x00, 0x00, 0x00, 0x0c, 0x0c}},
    {',', {0x00, 0x00, 0x00, 0x00, 0x0c, 0x04, 0x08}},
    {'(', {0x02, 0x04, 0x08, 0x08, 0x08, 0x04, 0x02}},
    {')', {0x08, 0x04, 0x02, 0x02, 0x02, 0x04, 0x08}},
    {'/', {0x00, 0x01, 0x02, 0x04, 0x08, 0x10, 0x00}},
    {':', {0x00, 0x0c, 0x0c, 0x00, 0x0c, 0x0c, 0x00}},
    {'_', {0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x1f}},
    {'+', {0x00, 0x04, 0x04, 0x1f, 0x04, 0x04, 0x00}},
    {'=', {0x00, 0x00, 0x1f, 0x00, 0x1f, 0x00, 0x00}},
    {'%', {0x18, 0x19, 0x02, 0x04, 0x08, 0x13, 0x03}},
    {'?', {0x0e, 0x11, 0x01, 0x02, 0x04, 0x00, 0x04}},
};

const std::array<uint8_t, 7>& glyph(char c) {
  if (c >= 'a' && c <= 'z') c = static_cast<char>(c - 'a' + 'A');
  static const std::array<uint8_t, 7> blank{};
  if (c == ' ') return blank;
  const Glyph* unknown = nullptr;
  for (const Glyph& g : kFont) {
    if (g.c == c) return g.rows;
    if (g.c == '?') unknown = &g;
  }
  return unknown->rows;
}

}  // namespace

int Canvas::text(int x, int y, std::string_view s, std::array<uint8_t, 3> c, int scale) {
  for (size_t i = 0; i < s.size(); ++i) {
    const auto& g = glyph(s[i]);
    const int gx = x + static_cast<int>(i) * 6 * scale;
    for (int r = 0; r < kTextHeight; ++r)
      for (int k = 0; k < 5; ++k)
        if (g[static_cast<size_t>(r)] & (0x10 >> k))
          rect(gx + k * scale, y + r * scale, gx + (k + 1) * scale, y + (r + 1) * scale, c);
  }
  return text_width(s, scale);
}

void Canvas::text_up(int x, int y, std::string_view s, std::array<uint8_t, 3> c, int scale) {
  // Font column k of glyph i goes up from y; font row r goes right from x.
  for (size_t i = 0; i < s.size(); ++i) {
    const auto& g = glyph(s[i]);
    const int gy = y - static_cast<int>(i) * 6 * scale;
    for (int r = 0; r < kTextHeight; ++r)
      for (int k = 0; k < 5; ++k)
        if (g[static_cast<size_t>(r)] & (0x10 >> k))
          rect(x + r * scale, gy - (k + 1) * scale, x + (r + 1) * scale, gy - k * scale, c);
  }
}

std::array<uint8_t, 3> palette(int i) {
  static const std::array<uint8_t, 3> p[] = {{220, 50, 32},   {30, 120, 200}, {40, 160, 60},
                                             {230, 150, 0},   {140, 60, 170}, {0, 170, 170},
                                             {120, 120, 120}, {200, 80, 140}};
  return p[i % 8];
}

}  // namespace candela::tools
