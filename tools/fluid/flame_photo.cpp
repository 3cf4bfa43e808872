#include "flame_photo.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "core/random.h"

namespace candela::fluid {
namespace {

// Smooth value noise on a periodic lattice of random values.
class ValueNoise {
 public:
  ValueNoise(int size, Pcg32& rng) : n_(size), v_(static_cast<size_t>(size) * size) {
    for (float& x : v_) x = static_cast<float>(rng.unit_double());
  }
  double at(double x, double y) const {
    const double fx = std::floor(x), fy = std::floor(y);
    const int x0 = wrap(static_cast<long>(fx)), y0 = wrap(static_cast<long>(fy));
    const int x1 = wrap(x0 + 1L), y1 = wrap(y0 + 1L);
    const double tx = smooth(x - fx), ty = smooth(y - fy);
    const double a = get(x0, y0) + (get(x1, y0) - get(x0, y0)) * tx;
    const double b = get(x0, y1) + (get(x1, y1) - get(x0, y1)) * tx;
    return a + (b - a) * ty;
  }

 private:
  static double smooth(double t) { return t * t * (3.0 - 2.0 * t); }
  int wrap(long i) const { return static_cast<int>(((i % n_) + n_) % n_); }
  double get(int x, int y) const { return v_[static_cast<size_t>(y) * n_ + x]; }
  int n_;
  std::vector<float> v_;
};

}  // namespace

Image render_flame_photo(int width, int height, uint64_t seed, bool with_alpha) {
  if (width < 16 || height < 16 || width > 4096 || height > 4096)
    throw std::invalid_argument("flame photo size: 16..4096 pixels each way");
  Pcg32 rng(seed, 0xf1a3e);
  ValueNoise noise(64, rng);
  Image img;
  img.width = width;
  img.height = height;
  img.channels = with_alpha ? 4 : 3;
  img.pixels.assign(static_cast<size_t>(width) * height * img.channels, 0);
  for (int y = 0; y < height; ++y) {
    // v: 0 at the base (bottom, a little above the edge) .. 1 at the tip.
    const double v = (height - 1 - y) / (0.92 * height) - 0.04;
    for (int x = 0; x < width; ++x) {
      const double u = (x + 0.5) / width - 0.5;
      // Fractal noise, stretched upward like rising flame tongues.
      double n = 0.0, amp = 0.5, freq = 4.0;
      for (int o = 0; o < 4; ++o) {
        n += amp * noise.at(x * freq / width + 17.0 * o, y * freq * 0.35 / height + 5.0 * o);
        amp *= 0.5;
        freq *= 2.0;
      }
      // Teardrop half-width: round at the base, tapering to a tip; the noise
      // frays its edge.
      const double vv = std::clamp(v, 0.0, 1.0);
      const double half = 0.42 * std::sqrt(std::max(0.0, vv)) * std::pow(1.0 - vv, 0.8) + 1e-6;
      const double edge = 1.0 - std::fabs(u) / half + 0.6 * (n - 0.5);
      double intensity = (v < 0.0 || v > 1.0) ? 0.0 : std::clamp(edge * 2.2, 0.0, 1.0);
      intensity *= std::clamp(0.75 + 1.2 * (n - 0.5), 0.1, 1.0);  // inner detail
      intensity *= std::clamp(1.2 - 0.7 * vv, 0.0, 1.0);          // dimmer toward the tip
      // Colour ramp: deep red -> orange -> pale yellow as it gets hotter.
      const double i = std::clamp(intensity, 0.0, 1.0);
      const double r = std::clamp(0.35 + 1.3 * i, 0.0, 1.0);
      const double g = std::clamp(-0.1 + 1.1 * i * i + 0.3 * i, 0.0, 1.0);
      const double b = std::clamp(1.3 * i * i * i * i - 0.15, 0.0, 1.0);
      uint8_t* p = img.row(y) + static_cast<size_t>(x) * img.channels;
      const double a = with_alpha ? std::clamp(i * 1.3, 0.0, 1.0) : 1.0;
      // With alpha the colour is straight (not premultiplied); without it the
      // flame is composited over black.
      const double k = with_alpha ? 1.0 : std::clamp(i * 1.3, 0.0, 1.0);
      p[0] = static_cast<uint8_t>(std::lround(255.0 * r * k));
      p[1] = static_cast<uint8_t>(std::lround(255.0 * g * k));
      p[2] = static_cast<uint8_t>(std::lround(255.0 * b * k));
      if (with_alpha) p[3] = static_cast<uint8_t>(std::lround(255.0 * a));
    }
  }
  return img;
}

}  // namespace candela::fluid
