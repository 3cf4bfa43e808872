#include "core/image.h"

#include <png.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/file_read.h"

namespace candela {
namespace {

[[noreturn]] void png_error_fn(png_structp png, png_const_charp msg) {
  auto* what = static_cast<std::string*>(png_get_error_ptr(png));
  if (what) *what = msg;
  png_longjmp(png, 1);
}
void png_warning_fn(png_structp, png_const_charp) {}

}  // namespace

namespace {

struct MemoryReader {
  const std::string* bytes;
  size_t at;
};

void read_from_memory(png_structp png, png_bytep out, png_size_t n) {
  auto* r = static_cast<MemoryReader*>(png_get_io_ptr(png));
  if (n > r->bytes->size() - r->at) png_error(png, "unexpected end of file");
  std::memcpy(out, r->bytes->data() + r->at, n);
  r->at += n;
}

struct Decoded {
  uint32_t width = 0, height = 0;
  int channels = 0;
};

// The stored samples (libpng's low-level API; only trivially destructible
// locals here, as libpng reports errors by longjmp). No gamma or colour-space
// conversion: footage from ffmpeg carries gAMA chunks that libpng's simplified
// API would apply, which darkens it (64 became 44) and makes the frames differ
// from what every other tool (PIL, the eval scripts, `candela-tool measure`)
// reads. Palettes and tRNS are expanded, 16-bit samples cut to their high byte.
// `pixels` is sized by `grow` once the header has been checked.
template <typename Grow>
bool decode(MemoryReader& in, Decoded& out, std::string& what, Grow grow) {
  png_structp png =
      png_create_read_struct(PNG_LIBPNG_VER_STRING, &what, png_error_fn, png_warning_fn);
  if (!png) {
    what = "out of memory";
    return false;
  }
  png_infop info = png_create_info_struct(png);
  png_bytepp rows = nullptr;
  if (!info || setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, info ? &info : nullptr, nullptr);
    std::free(rows);
    return false;
  }
  png_set_read_fn(png, &in, read_from_memory);
  png_read_info(png, info);
  out.width = png_get_image_width(png, info);
  out.height = png_get_image_height(png, info);
  // A small file can declare a huge image (a decompression bomb): bound what it unpacks to.
  if (static_cast<uint64_t>(out.width) * out.height > kMaxPngPixels) {
    what = "a " + std::to_string(out.width) + "x" + std::to_string(out.height) +
           " image, more than the " + std::to_string(kMaxPngPixels >> 20) +
           " Mpixel limit for a PNG image";
    png_destroy_read_struct(&png, &info, nullptr);
    return false;
  }
  const int type = png_get_color_type(png, info);
  if (type == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png);
  if (type == PNG_COLOR_TYPE_GRAY && png_get_bit_depth(png, info) < 8)
    png_set_expand_gray_1_2_4_to_8(png);
  if (png_get_valid(png, info, PNG_INFO_tRNS)) png_set_tRNS_to_alpha(png);
  png_set_strip_16(png);
  png_set_interlace_handling(png);
  png_read_update_info(png, info);
  out.channels = png_get_channels(png, info);
  const size_t stride = png_get_rowbytes(png, info);
  uint8_t* pixels = grow(stride * out.height);
  rows = static_cast<png_bytepp>(std::malloc(sizeof(png_bytep) * out.height));
  if (!rows) png_error(png, "out of memory");
  for (uint32_t y = 0; y < out.height; ++y) rows[y] = pixels + stride * y;
  png_read_image(png, rows);
  png_read_end(png, nullptr);
  png_destroy_read_struct(&png, &info, nullptr);
  std::free(rows);
  return true;
}

// Gray from RGB as PIL's convert('L') (ITU-R 601-2 luma, 16-bit fixed point).
uint8_t luma(const uint8_t* p) {
  return static_cast<uint8_t>((p[0] * 19595u + p[1] * 38470u + p[2] * 7471u + 0x8000u) >> 16);
}

}  // namespace

Image read_png(const std::string& path, int want_channels) {
  const std::string bytes = read_bounded_file(path, FileKind::kImage);
  if (bytes.size() < 8 || png_sig_cmp(reinterpret_cast<png_const_bytep>(bytes.data()), 0, 8) != 0)
    throw ConfigError(path, "", "expected a PNG file (bad signature)");
  MemoryReader in{&bytes, 0};
  Decoded d;
  std::string what;
  std::vector<uint8_t> stored;
  if (!decode(in, d, what, [&](size_t n) {
        stored.resize(n);
        return stored.data();
      }))
    throw ConfigError(path, "", (what.rfind("a ", 0) == 0 ? "" : "unreadable PNG: ") + what);
  const int from = d.channels;
  const int to = want_channels >= 1 && want_channels <= 4 ? want_channels : from;
  Image out;
  out.width = static_cast<int>(d.width);
  out.height = static_cast<int>(d.height);
  out.channels = to;
  if (to == from) {
    out.pixels = std::move(stored);
    return out;
  }
  const size_t px = static_cast<size_t>(d.width) * d.height;
  out.pixels.resize(px * to);
  const bool from_alpha = from == 2 || from == 4;
  for (size_t i = 0; i < px; ++i) {
    const uint8_t* s = stored.data() + i * from;
    uint8_t* o = out.pixels.data() + i * to;
    const uint8_t alpha = from_alpha ? s[from - 1] : 255;
    if (to <= 2) {
      o[0] = from >= 3 ? luma(s) : s[0];
    } else {
      o[0] = s[0];
      o[1] = from >= 3 ? s[1] : s[0];
      o[2] = from >= 3 ? s[2] : s[0];
    }
    if (to == 2 || to == 4) o[to - 1] = alpha;
  }
  return out;
}

void write_png(const std::string& path, int width, int height, int channels, const uint8_t* data,
               int stride) {
  write_atomic(path, [&](FILE* f) {
    std::string what;
    png_structp png =
        png_create_write_struct(PNG_LIBPNG_VER_STRING, &what, png_error_fn, png_warning_fn);
    png_infop info = png ? png_create_info_struct(png) : nullptr;
    if (!png || !info) {
      png_destroy_write_struct(&png, &info);
      throw RuntimeError(path + ": out of memory");
    }
    if (setjmp(png_jmpbuf(png))) {
      png_destroy_write_struct(&png, &info);
      throw RuntimeError(path + ": " + what);
    }
    png_init_io(png, f);
    static const int kTypes[] = {0, PNG_COLOR_TYPE_GRAY, PNG_COLOR_TYPE_GRAY_ALPHA,
                                 PNG_COLOR_TYPE_RGB, PNG_COLOR_TYPE_RGBA};
    png_set_IHDR(png, info, width, height, 8, kTypes[channels], PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_set_compression_level(png, 3);  // frame dumps: speed over size
    png_write_info(png, info);
    const size_t step =
        stride ? static_cast<size_t>(stride) : static_cast<size_t>(width) * channels;
    for (int y = 0; y < height; ++y) png_write_row(png, data + step * y);
    png_write_end(png, nullptr);
    png_destroy_write_struct(&png, &info);
  });
}

void write_png(const std::string& path, const Image& image) {
  write_png(path, image.width, image.height, image.channels, image.pixels.data());
}

void gaussian_blur(std::vector<float>& pixels, int width, int height, int channels, double sigma) {
  if (!(sigma >= 0.5)) return;
  const int r = static_cast<int>(std::ceil(3.0 * sigma));
  std::vector<double> k(2 * r + 1);
  double sum = 0.0;
  for (int i = -r; i <= r; ++i) sum += k[i + r] = std::exp(-0.5 * i * i / (sigma * sigma));
  for (double& w : k) w /= sum;
  std::vector<float> tmp(pixels.size());
  // Along rows, then along columns.
  for (int pass = 0; pass < 2; ++pass) {
    const int n = pass == 0 ? width : height, m = pass == 0 ? height : width;
    for (int a = 0; a < m; ++a)
      for (int b = 0; b < n; ++b) {
        const size_t out =
            pass == 0 ? static_cast<size_t>(a) * width + b : static_cast<size_t>(b) * width + a;
        for (int c = 0; c < channels; ++c) {
          double acc = 0.0;
          for (int i = -r; i <= r; ++i) {
            const int bb = std::clamp(b + i, 0, n - 1);
            const size_t at = pass == 0 ? static_cast<size_t>(a) * width + bb
                                        : static_cast<size_t>(bb) * width + a;
            acc += k[i + r] * pixels[channels * at + c];
          }
          tmp[channels * out + c] = static_cast<float>(acc);
        }
      }
    pixels.swap(tmp);
  }
}

}  // namespace candela
