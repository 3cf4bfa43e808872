// Loading a folder of frames as the scripts do (PIL: sorted *.png, convert('L')),
// and PIL's BILINEAR resize, bit for bit, so thresholds fall on the same pixels.
#include <png.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <string>

#include "core/error.h"
#include "measure/measure.h"

namespace candela::measure {

namespace fs = std::filesystem;

namespace {

// The stored samples, as PIL reads them: no gamma or colour-space conversion
// (real footage from ffmpeg carries gAMA chunks, which PIL ignores but libpng's
// simplified API, core's read_png, applies), palettes expanded, 16-bit samples
// cut to their high byte, alpha and tRNS ignored later by the gray conversion.
struct Png {
  int width = 0, height = 0, channels = 0;
  std::vector<uint8_t> pixels;
  std::vector<png_bytep> rows;
};

struct PngError {
  char message[200];
};

[[noreturn]] void on_png_error(png_structp png, png_const_charp msg) {
  auto* e = static_cast<PngError*>(png_get_error_ptr(png));
  std::snprintf(e->message, sizeof e->message, "%s", msg);
  png_longjmp(png, 1);
}
void on_png_warning(png_structp, png_const_charp) {}

// Only trivially destructible locals live here: libpng reports errors by longjmp.
bool decode_png(FILE* f, Png& out, PngError& err, int max_side) {
  png_structp png =
      png_create_read_struct(PNG_LIBPNG_VER_STRING, &err, on_png_error, on_png_warning);
  if (!png) {
    std::snprintf(err.message, sizeof err.message, "out of memory");
    return false;
  }
  png_infop info = png_create_info_struct(png);
  if (!info || setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, info ? &info : nullptr, nullptr);
    return false;
  }
  png_init_io(png, f);
  png_read_info(png, info);
  const png_uint_32 w = png_get_image_width(png, info), h = png_get_image_height(png, info);
  if (w > static_cast<png_uint_32>(max_side) || h > static_cast<png_uint_32>(max_side)) {
    std::snprintf(err.message, sizeof err.message, "frame is %ux%u, larger than %d px a side",
                  static_cast<unsigned>(w), static_cast<unsigned>(h), max_side);
    png_destroy_read_struct(&png, &info, nullptr);
    return false;
  }
  const int type = png_get_color_type(png, info);
  if (type == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png);
  if (type == PNG_COLOR_TYPE_GRAY && png_get_bit_depth(png, info) < 8)
    png_set_expand_gray_1_2_4_to_8(png);
  png_set_strip_16(png);
  png_set_interlace_handling(png);
  png_read_update_info(png, info);
  out.width = static_cast<int>(w);
  out.height = static_cast<int>(h);
  out.channels = png_get_channels(png, info);
  const size_t stride = png_get_rowbytes(png, info);
  out.pixels.resize(stride * h);
  out.rows.resize(h);
  for (png_uint_32 y = 0; y < h; ++y) out.rows[y] = out.pixels.data() + stride * y;
  png_read_image(png, out.rows.data());
  png_read_end(png, nullptr);
  png_destroy_read_struct(&png, &info, nullptr);
  return true;
}

Png read_png_samples(const std::string& path, int max_side) {
  struct Closer {
    void operator()(FILE* f) const { std::fclose(f); }
  };
  std::unique_ptr<FILE, Closer> f(std::fopen(path.c_str(), "rb"));
  if (!f) throw ConfigError(path, "", std::string("cannot open PNG: ") + std::strerror(errno));
  unsigned char sig[8];
  if (std::fread(sig, 1, 8, f.get()) != 8 || png_sig_cmp(sig, 0, 8) != 0)
    throw ConfigError(path, "", "unreadable PNG: not a PNG file (bad signature)");
  std::rewind(f.get());
  Png out;
  PngError err{};
  if (!decode_png(f.get(), out, err, max_side))
    throw ConfigError(path, "", std::string("unreadable PNG: ") + err.message);
  return out;
}

}  // namespace

void to_gray(const uint8_t* in, int channels, int width, uint8_t* out) {
  if (channels <= 2) {
    for (int x = 0; x < width; ++x) out[x] = in[x * channels];
    return;
  }
  for (int x = 0; x < width; ++x) {
    const uint8_t* p = in + x * channels;
    // Pillow's rgb2l (Convert.c): L24 in 16-bit fixed point, rounded.
    out[x] = static_cast<uint8_t>((p[0] * 19595u + p[1] * 38470u + p[2] * 7471u + 0x8000u) >> 16);
  }
}

Frames load_frames(const std::string& dir, const LoadLimits& limits) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec))
    throw ConfigError(dir, "", "expected a folder of PNG frames (not found or not a folder)");
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    std::string n = e.path().filename().string();
    std::string low = n;
    std::transform(low.begin(), low.end(), low.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (low.size() >= 4 && low.compare(low.size() - 4, 4, ".png") == 0) names.push_back(n);
  }
  if (ec) throw ConfigError(dir, "", "cannot list the folder: " + ec.message());
  if (names.empty()) throw ConfigError(dir, "", "no PNG frames (*.png) in this folder");
  std::sort(names.begin(), names.end());
  if (static_cast<int>(names.size()) > limits.max_frames) names.resize(limits.max_frames);

  Frames out;
  std::string first;
  std::vector<uint8_t> row;
  for (const std::string& n : names) {
    const std::string path = (fs::path(dir) / n).string();
    const Png im = read_png_samples(path, limits.max_side);  // errors name the file
    if (out.count == 0) {
      const size_t need = static_cast<size_t>(im.width) * im.height * names.size();
      if (need > limits.max_bytes)
        throw ConfigError(dir, "",
                          std::to_string(names.size()) + " frames of " + std::to_string(im.width) +
                              "x" + std::to_string(im.height) + " need " +
                              std::to_string(need >> 20) + " MiB, more than the " +
                              std::to_string(limits.max_bytes >> 20) +
                              " MiB limit (use fewer frames)");
      out.width = im.width;
      out.height = im.height;
      out.pixels.resize(need);
      first = path;
    } else if (im.width != out.width || im.height != out.height) {
      throw ConfigError(path, "",
                        "frame is " + std::to_string(im.width) + "x" + std::to_string(im.height) +
                            " but " + first + " is " + std::to_string(out.width) + "x" +
                            std::to_string(out.height) + " (all frames must be the same size)");
    }
    uint8_t* dst = out.frame(out.count);
    for (int y = 0; y < im.height; ++y)
      to_gray(im.rows[y], im.channels, im.width, dst + static_cast<size_t>(y) * im.width);
    ++out.count;
  }
  return out;
}

namespace {

constexpr int kPrecisionBits = 32 - 8 - 2;

// Pillow's precompute_coeffs + normalize_coeffs_8bpc for the BILINEAR filter
// (triangle, support 1, widened by the downscale factor).
struct Coeffs {
  int ksize = 0;
  std::vector<int> bounds;  // per output: first input, count
  std::vector<int32_t> k;   // ksize per output, fixed point
};

Coeffs precompute(int in_size, int out_size) {
  Coeffs c;
  const float in0 = 0.0f, in1 = static_cast<float>(in_size);
  double filterscale, scale;
  filterscale = scale = static_cast<double>(in1 - in0) / out_size;
  if (filterscale < 1.0) filterscale = 1.0;
  const double support = 1.0 * filterscale;
  c.ksize = static_cast<int>(std::ceil(support)) * 2 + 1;
  c.bounds.resize(static_cast<size_t>(out_size) * 2);
  c.k.assign(static_cast<size_t>(out_size) * c.ksize, 0);
  std::vector<double> kk(c.ksize);
  for (int xx = 0; xx < out_size; ++xx) {
    const double center = in0 + (xx + 0.5) * scale;
    double ww = 0.0;
    const double ss = 1.0 / filterscale;
    int xmin = static_cast<int>(center - support + 0.5);
    if (xmin < 0) xmin = 0;
    int xmax = static_cast<int>(center + support + 0.5);
    if (xmax > in_size) xmax = in_size;
    xmax -= xmin;
    for (int x = 0; x < xmax; ++x) {
      double t = (x + xmin - center + 0.5) * ss;
      if (t < 0.0) t = -t;
      const double w = t < 1.0 ? 1.0 - t : 0.0;
      kk[x] = w;
      ww += w;
    }
    for (int x = 0; x < xmax; ++x) {
      if (ww != 0.0) kk[x] /= ww;
      const double v = kk[x];
      c.k[static_cast<size_t>(xx) * c.ksize + x] =
          v < 0 ? static_cast<int>(-0.5 + v * (1 << kPrecisionBits))
                : static_cast<int>(0.5 + v * (1 << kPrecisionBits));
    }
    c.bounds[xx * 2] = xmin;
    c.bounds[xx * 2 + 1] = xmax;
  }
  return c;
}

inline uint8_t clip8(int v) {
  const int s = v >> kPrecisionBits;
  return static_cast<uint8_t>(s < 0 ? 0 : s > 255 ? 255 : s);
}

}  // namespace

Frames resize_bilinear_pil(const Frames& in, int width, int height) {
  Frames out;
  out.width = width;
  out.height = height;
  out.count = in.count;
  out.pixels.resize(out.frame_size() * in.count);
  if (width == in.width && height == in.height) {
    out.pixels = in.pixels;
    return out;
  }
  const bool need_h = width != in.width, need_v = height != in.height;
  const Coeffs ch = precompute(in.width, width);
  Coeffs cv = precompute(in.height, height);
  // Only the source rows the vertical pass reads are resampled horizontally.
  const int y_first = cv.bounds[0];
  const int y_last = cv.bounds[height * 2 - 2] + cv.bounds[height * 2 - 1];
  if (need_h)
    for (int i = 0; i < height; ++i) cv.bounds[i * 2] -= y_first;
  const int tmp_h = need_h ? y_last - y_first : in.height;
  const int tmp_w = need_h ? width : in.width;
  std::vector<uint8_t> tmp(static_cast<size_t>(tmp_w) * tmp_h);
  for (int t = 0; t < in.count; ++t) {
    const uint8_t* src = in.frame(t);
    const uint8_t* mid = src;
    if (need_h) {
      for (int yy = 0; yy < tmp_h; ++yy) {
        const uint8_t* row = src + static_cast<size_t>(yy + y_first) * in.width;
        for (int xx = 0; xx < width; ++xx) {
          const int xmin = ch.bounds[xx * 2], xmax = ch.bounds[xx * 2 + 1];
          const int32_t* k = &ch.k[static_cast<size_t>(xx) * ch.ksize];
          int ss = 1 << (kPrecisionBits - 1);
          for (int x = 0; x < xmax; ++x) ss += row[x + xmin] * k[x];
          tmp[static_cast<size_t>(yy) * width + xx] = clip8(ss);
        }
      }
      mid = tmp.data();
    }
    uint8_t* dst = out.frame(t);
    if (!need_v) {
      std::copy(mid, mid + out.frame_size(), dst);
      continue;
    }
    for (int yy = 0; yy < height; ++yy) {
      const int ymin = cv.bounds[yy * 2], ymax = cv.bounds[yy * 2 + 1];
      const int32_t* k = &cv.k[static_cast<size_t>(yy) * cv.ksize];
      for (int xx = 0; xx < tmp_w; ++xx) {
        int ss = 1 << (kPrecisionBits - 1);
        for (int y = 0; y < ymax; ++y) ss += mid[static_cast<size_t>(y + ymin) * tmp_w + xx] * k[y];
        dst[static_cast<size_t>(yy) * width + xx] = clip8(ss);
      }
    }
  }
  return out;
}

}  // namespace candela::measure
