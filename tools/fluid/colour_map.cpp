#include "colour_map.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace candela::fluid {
namespace {

double lobe(double x, double mu, double s1, double s2) {
  const double t = (x - mu) / (x < mu ? s1 : s2);
  return std::exp(-0.5 * t * t);
}

uint8_t encode_srgb(double linear) {
  linear = std::clamp(linear, 0.0, 1.0);
  const double e =
      linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
  return static_cast<uint8_t>(std::lround(e * 255.0));
}

// Unnormalised CIE XYZ of a Planck radiator at `kelvin` (Wyman-Sloan-Shirley
// matching functions, 5 nm steps).
std::array<double, 3> black_body_xyz(double kelvin) {
  kelvin = std::max(kelvin, 100.0);
  double X = 0.0, Y = 0.0, Z = 0.0;
  for (double nm = 380.0; nm <= 780.0; nm += 5.0) {
    const double l = nm * 1e-9;
    // Planck's law up to a constant factor (normalised by the callers).
    const double planck = 1.0 / (l * l * l * l * l * (std::exp(1.4387769e-2 / (l * kelvin)) - 1.0));
    const double xb = 1.056 * lobe(nm, 599.8, 37.9, 31.0) + 0.362 * lobe(nm, 442.0, 16.0, 26.7) -
                      0.065 * lobe(nm, 501.1, 20.4, 26.2);
    const double yb = 0.821 * lobe(nm, 568.8, 46.9, 40.5) + 0.286 * lobe(nm, 530.9, 16.3, 31.1);
    const double zb = 1.217 * lobe(nm, 437.0, 11.8, 36.0) + 0.681 * lobe(nm, 459.0, 26.0, 13.8);
    X += planck * xb;
    Y += planck * yb;
    Z += planck * zb;
  }
  return {X, Y, Z};
}

}  // namespace

double black_body_luminance(double kelvin) {
  static const double ref = black_body_xyz(1500.0)[1];
  return black_body_xyz(kelvin)[1] / ref;
}

double soft_clip(double x, double knee) {
  if (x <= knee) return std::max(x, 0.0);
  const double r = 1.0 - knee;  // continuous value and slope at the knee
  return 1.0 - r * std::exp(-(x - knee) / r);
}

RadianceTable::RadianceTable(double t_ambient, double t_reference) : lo(t_ambient) {
  const double y_ref = black_body_luminance(t_reference);
  for (double k = lo; k <= 2.0 * t_reference + step; k += step)
    lum.push_back(black_body_luminance(k) / y_ref);
}

double RadianceTable::at(double kelvin) const {
  const double f = std::clamp((kelvin - lo) / step, 0.0, lum.size() - 1.001);
  const auto k = static_cast<size_t>(f);
  return lum[k] + (lum[k + 1] - lum[k]) * (f - k);
}

Image render_radiance(const Grid2& t, double t_ambient, double t_reference, ColourMode mode,
                      const Camera& cam, int scale, const Grid2* fuel) {
  const bool soot = fuel && cam.soot > 0.0 && fuel->width == t.width && fuel->height == t.height;
  Image img;
  img.width = t.width * scale;
  img.height = t.height * scale;
  img.channels = mode == ColourMode::kGray ? 1 : 3;
  img.pixels.resize(static_cast<size_t>(img.width) * img.height * img.channels);
  // Y(T)/Y(T_ref) and the Planck colour in 10 K steps up to twice T_ref.
  const RadianceTable table(t_ambient, t_reference);
  const double step = table.step, lo = table.lo;
  const std::vector<double>& lum = table.lum;
  std::vector<std::array<double, 3>> rgb;
  for (double k = lo; k <= 2.0 * t_reference + step; k += step) {
    if (mode != ColourMode::kGray) {
      auto c = black_body_rgb(k);
      const double l = 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
      for (double& x : c) x /= std::max(l, 1e-12);  // unit luminance, Planck hue
      rgb.push_back(c);
    }
  }
  for (int y = 0; y < img.height; ++y) {
    uint8_t* row = img.row(y);
    const double gy = (img.height - 1 - y + 0.5) / scale - 0.5;  // grid rows run bottom-up
    for (int x = 0; x < img.width; ++x) {
      const double gx = (x + 0.5) / scale - 0.5;
      const double f = std::clamp((t.sample(gx, gy) - lo) / step, 0.0, lum.size() - 1.001);
      const auto k = static_cast<size_t>(f);
      const double a = f - k;
      double e = cam.exposure * (lum[k] + (lum[k + 1] - lum[k]) * a);
      if (soot) e *= 1.0 - std::exp(-std::max(0.0, fuel->sample(gx, gy)) / cam.soot);
      if (mode == ColourMode::kGray) {
        row[x] = encode_srgb(soft_clip(e, cam.knee));
      } else {
        for (int c = 0; c < 3; ++c)
          row[3 * x + c] = encode_srgb(soft_clip(e * rgb[k][c], cam.knee));
      }
    }
  }
  return img;
}

void add_radiance(const Grid2& t, const Grid2* fuel, const RadianceTable& table, const Camera& cam,
                  const SlicePlacement& at, int canvas_width, int canvas_height,
                  std::vector<float>& canvas) {
  canvas.resize(static_cast<size_t>(canvas_width) * canvas_height, 0.0f);
  const bool soot = fuel && cam.soot > 0.0 && fuel->width == t.width && fuel->height == t.height;
  // Only the canvas pixels the grid covers.
  const int x0 = std::max(0, static_cast<int>(std::floor(at.left)));
  const int x1 = std::min(canvas_width, static_cast<int>(std::ceil(at.left + t.width * at.scale)));
  const int y1 = std::min(canvas_height, static_cast<int>(std::ceil(canvas_height - at.bottom)));
  const int y0 = std::max(0, static_cast<int>(std::floor(y1 - t.height * at.scale)));
  // The fades (smooth, so no new edge): per column once, per row below.
  auto fade = [](double d, double band) {  // d: cells from the edge
    if (band <= 0.0) return 1.0;
    const double u = std::clamp(d / band, 0.0, 1.0);
    return u * u * (3.0 - 2.0 * u);
  };
  std::vector<double> window_x(static_cast<size_t>(std::max(0, x1 - x0)), 1.0);
  for (int x = x0; x < x1; ++x) {
    const double gx = (x + 0.5 - at.left) / at.scale - 0.5;
    window_x[x - x0] = fade(std::min(gx + 0.5, t.width - 0.5 - gx), at.fade_sides * t.width);
  }
  for (int y = y0; y < y1; ++y) {
    float* row = canvas.data() + static_cast<size_t>(y) * canvas_width;
    const double gy = (canvas_height - 1 - y - at.bottom + 0.5) / at.scale - 0.5;
    if (gy < -0.5 || gy > t.height - 0.5) continue;
    const double window_y = fade(t.height - 0.5 - gy, at.fade_top * t.height);
    for (int x = x0; x < x1; ++x) {
      double gx = (x + 0.5 - at.left) / at.scale - 0.5;
      if (at.mirror) gx = t.width - 1 - gx;
      if (gx < -0.5 || gx > t.width - 0.5) continue;
      double e = cam.exposure * table.at(t.sample(gx, gy));
      if (soot) e *= 1.0 - std::exp(-std::max(0.0, fuel->sample(gx, gy)) / cam.soot);
      row[x] += static_cast<float>(e * at.gain * window_x[x - x0] * window_y);
    }
  }
}

Image finish_radiance(const std::vector<float>& canvas, int width, int height, const Camera& cam) {
  Image img;
  img.width = width;
  img.height = height;
  img.channels = 1;
  img.pixels.resize(static_cast<size_t>(width) * height);
  std::vector<float> glow;
  if (cam.glow > 0.0) {
    glow = canvas;
    gaussian_blur(glow, width, height, 1, cam.glow_radius);
  }
  std::vector<float> clipped(canvas.size());
  for (size_t i = 0; i < clipped.size(); ++i) {
    const double light = canvas[i] + (glow.empty() ? 0.0 : cam.glow * glow[i]);
    clipped[i] = static_cast<float>(soft_clip(light, cam.knee));
  }
  std::vector<float> haze;
  if (cam.haze > 0.0) {
    haze = clipped;
    gaussian_blur(haze, width, height, 1, cam.haze_radius);
  }
  for (size_t i = 0; i < img.pixels.size(); ++i) {
    const double light = clipped[i] + (haze.empty() ? 0.0 : cam.haze * haze[i]);
    img.pixels[i] = encode_srgb(std::min(1.0, light));
  }
  return img;
}

std::array<double, 3> black_body_rgb(double kelvin) {
  const auto [X, Y, Z] = black_body_xyz(kelvin);
  std::array<double, 3> rgb = {3.2406 * X - 1.5372 * Y - 0.4986 * Z,
                               -0.9689 * X + 1.8758 * Y + 0.0415 * Z,
                               0.0557 * X - 0.2040 * Y + 1.0570 * Z};
  for (double& c : rgb) c = std::max(c, 0.0);
  const double m = std::max({rgb[0], rgb[1], rgb[2], 1e-300});
  for (double& c : rgb) c /= m;
  return rgb;
}

Image render_temperature(const Grid2& t, double t_ambient, double t_reference, ColourMode mode,
                         int scale) {
  Image img;
  img.width = t.width * scale;
  img.height = t.height * scale;
  img.channels = mode == ColourMode::kGray ? 1 : 3;
  img.pixels.resize(static_cast<size_t>(img.width) * img.height * img.channels);
  // Black-body chromaticity in 25 K steps between ambient and reference.
  std::vector<std::array<double, 3>> lut;
  const double step = 25.0;
  if (mode == ColourMode::kBlackBody)
    for (double k = t_ambient; k <= t_reference + step; k += step) lut.push_back(black_body_rgb(k));
  const double span = t_reference - t_ambient;
  for (int y = 0; y < img.height; ++y) {
    uint8_t* row = img.row(y);
    const double gy = (img.height - 1 - y + 0.5) / scale - 0.5;  // grid rows run bottom-up
    for (int x = 0; x < img.width; ++x) {
      const double gx = (x + 0.5) / scale - 0.5;
      const double kelvin = t.sample(gx, gy);
      const double s = std::clamp((kelvin - t_ambient) / span, 0.0, 1.0);
      if (mode == ColourMode::kGray) {
        row[x] = static_cast<uint8_t>(std::lround(s * 255.0));
      } else {
        const size_t k = std::min(
            lut.size() - 1,
            static_cast<size_t>((kelvin - t_ambient) < 0 ? 0.0 : (kelvin - t_ambient) / step));
        for (int c = 0; c < 3; ++c) row[3 * x + c] = encode_srgb(lut[k][c] * s);
      }
    }
  }
  return img;
}

}  // namespace candela::fluid
