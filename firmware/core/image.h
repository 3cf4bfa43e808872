// 8-bit images and PNG files (libpng). Rows are stored top to bottom.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace candela {

struct Image {
  int width = 0;
  int height = 0;
  int channels = 0;  // 1 = gray, 2 = gray+alpha, 3 = RGB, 4 = RGBA
  std::vector<uint8_t> pixels;

  uint8_t* row(int y) { return pixels.data() + static_cast<size_t>(y) * width * channels; }
  const uint8_t* row(int y) const {
    return pixels.data() + static_cast<size_t>(y) * width * channels;
  }
  uint8_t at(int x, int y, int c = 0) const { return row(y)[x * channels + c]; }
};

// Decoded images beyond this many pixels are refused (a small PNG can declare a huge one).
inline constexpr uint64_t kMaxPngPixels = uint64_t{64} << 20;

// Reads any PNG (a regular file within the PNG size limit, core/file_read.h),
// converted to `want_channels` (0 = as stored, 8-bit).
// Throws ConfigError naming the file and what is wrong with it.
Image read_png(const std::string& path, int want_channels = 0);
// Writes atomically (temporary file + rename). Throws RuntimeError on failure.
void write_png(const std::string& path, const Image& image);
// The same, from a raw buffer; stride in bytes (0 = tightly packed).
void write_png(const std::string& path, int width, int height, int channels, const uint8_t* data,
               int stride = 0);

// Separable Gaussian blur (sigma in pixels, kernel cut at 3 sigma) of a float
// image of `channels` interleaved channels, rows top-down, in place; edges
// clamped (the light beyond the edge is the edge's own). Sigma below 0.5
// leaves it as it is. For the tools' glows; the runtime blurs on the GPU.
void gaussian_blur(std::vector<float>& pixels, int width, int height, int channels, double sigma);

}  // namespace candela
