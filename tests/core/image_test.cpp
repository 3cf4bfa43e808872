// core/image: PNG samples are read as stored, whatever colour metadata the
// file carries, so a frame means the same to ingest, the runtime and measure.
#include "core/image.h"

#include <gtest/gtest.h>
#include <png.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

// A PNG as ffmpeg writes flame footage: 8-bit, with a gAMA chunk (1/2.8).
void write_with_gamma(const std::string& path, int channels, const std::vector<uint8_t>& px, int w,
                      int h) {
  FILE* f = std::fopen(path.c_str(), "wb");
  ASSERT_NE(f, nullptr);
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png_create_info_struct(png);
  png_init_io(png, f);
  png_set_IHDR(png, info, w, h, 8, channels == 1 ? PNG_COLOR_TYPE_GRAY : PNG_COLOR_TYPE_RGB,
               PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_set_gAMA(png, info, 1.0 / 2.8);
  png_write_info(png, info);
  for (int y = 0; y < h; ++y)
    png_write_row(png, const_cast<png_bytep>(px.data()) + static_cast<size_t>(y) * w * channels);
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  std::fclose(f);
}

std::string scratch(const char* name) {
  return (fs::temp_directory_path() / (std::string(name) + std::to_string(getpid()) + ".png"))
      .string();
}

TEST(ReadPng, GrayWithAGammaChunkReadsAsStored) {
  const std::string p = scratch("gamma_gray");
  const std::vector<uint8_t> px = {0, 44, 64, 128, 200, 255};
  write_with_gamma(p, 1, px, 6, 1);
  const candela::Image im = candela::read_png(p);
  ASSERT_EQ(im.channels, 1);
  EXPECT_EQ(im.pixels, px);  // libpng's simplified API gave 64 -> 44 here
  const candela::Image rgba = candela::read_png(p, 4);
  ASSERT_EQ(rgba.channels, 4);
  EXPECT_EQ(rgba.at(2, 0, 0), 64);
  EXPECT_EQ(rgba.at(2, 0, 1), 64);
  EXPECT_EQ(rgba.at(2, 0, 3), 255);
  fs::remove(p);
}

TEST(ReadPng, ColourToGrayIsPilsLuma) {
  // PIL's convert('L'), which the eval scripts use: (R 19595 + G 38470 + B 7471 + 0x8000) >> 16.
  const std::string p = scratch("gamma_rgb");
  const std::vector<uint8_t> px = {255, 0, 0, 0, 255, 0, 0, 0, 255, 250, 120, 20};
  write_with_gamma(p, 3, px, 4, 1);
  const candela::Image g = candela::read_png(p, 1);
  ASSERT_EQ(g.channels, 1);
  EXPECT_EQ(g.at(0, 0), 76);
  EXPECT_EQ(g.at(1, 0), 150);
  EXPECT_EQ(g.at(2, 0), 29);
  EXPECT_EQ(g.at(3, 0), (250 * 19595u + 120 * 38470u + 20 * 7471u + 0x8000u) >> 16);
  const candela::Image rgb = candela::read_png(p);
  ASSERT_EQ(rgb.channels, 3);
  EXPECT_EQ(rgb.pixels, px);
  fs::remove(p);
}

}  // namespace
