// Loading a folder of frames as the scripts do (PIL: sorted *.png, convert('L')),
// and PIL's BILINEAR resize, bit for bit, so thresholds fall on the same pixels.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>

#include "core/error.h"
#include "core/image.h"
#include "measure/measure.h"

namespace candela::measure {

namespace fs = std::filesystem;

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
    // Stored samples, gray as PIL's convert('L'); errors name the file.
    const Image im = read_png(path, 1);
    if (im.width > limits.max_side || im.height > limits.max_side)
      throw ConfigError(path, "",
                        "frame is " + std::to_string(im.width) + "x" + std::to_string(im.height) +
                            ", larger than " + std::to_string(limits.max_side) + " px a side");
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
    std::copy(im.pixels.begin(), im.pixels.end(), out.frame(out.count));
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
