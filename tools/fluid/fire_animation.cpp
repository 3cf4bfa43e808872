#include "fire_animation.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>

namespace candela::fluid {

void validate(const AnimateParams& p) {
  validate(p.synth);
  if (p.key_interval < 1 || p.key_interval > 10000)
    throw std::invalid_argument("key-interval: 1..10000 frames");
  if (p.dissolve < 0 || p.dissolve >= p.key_interval)
    throw std::invalid_argument("dissolve: 0 <= m < key-interval");
  if (p.scale < 1 || p.scale > 16) throw std::invalid_argument("scale: 1..16");
}

std::vector<float> temperature_target(const FieldFrame& f, int scale) {
  const Grid2& t = f.temperature;
  const int w = t.width * scale, h = t.height * scale;
  std::vector<float> out(static_cast<size_t>(w) * h);
  const double span = f.t_reference - f.t_ambient;
  for (int y = 0; y < h; ++y) {
    const double gy = (h - 1 - y + 0.5) / scale - 0.5;
    for (int x = 0; x < w; ++x) {
      const double gx = (x + 0.5) / scale - 0.5;
      out[static_cast<size_t>(y) * w + x] =
          static_cast<float>(std::clamp((t.sample(gx, gy) - f.t_ambient) / span, 0.0, 1.0));
    }
  }
  return out;
}

RgbImage advect_image(const RgbImage& img, const FieldFrame& f, int scale, double seconds) {
  if (!f.has_velocity)
    throw std::invalid_argument(
        "advect: the field file has no velocity (needed between key frames)");
  RgbImage out = img;
  const int w = img.width, h = img.height;
  auto sample = [&](double x, double y, float* dst) {
    x = std::clamp(x, 0.0, w - 1.0);
    y = std::clamp(y, 0.0, h - 1.0);
    const int x0 = std::min(static_cast<int>(x), std::max(w - 2, 0));
    const int y0 = std::min(static_cast<int>(y), std::max(h - 2, 0));
    const int x1 = std::min(x0 + 1, w - 1), y1 = std::min(y0 + 1, h - 1);
    const float fx = static_cast<float>(x - x0), fy = static_cast<float>(y - y0);
    for (int c = 0; c < 3; ++c) {
      const float a = img.at(x0, y0)[c] + (img.at(x1, y0)[c] - img.at(x0, y0)[c]) * fx;
      const float b = img.at(x0, y1)[c] + (img.at(x1, y1)[c] - img.at(x0, y1)[c]) * fx;
      dst[c] = a + (b - a) * fy;
    }
  };
  const double k = scale * seconds;  // cells/s -> output pixels
  for (int y = 0; y < h; ++y) {
    const double gy = (h - 1 - y + 0.5) / scale - 0.5;
    for (int x = 0; x < w; ++x) {
      const double gx = (x + 0.5) / scale - 0.5;
      const double dx = f.u.sample(gx, gy) * k;
      const double dy = -f.v.sample(gx, gy) * k;  // v > 0 is up, image y runs down
      sample(x - dx, y - dy, out.at(x, y));
    }
  }
  return out;
}

AnimateStats animate_fire(const Exemplar& photo, const AnimateParams& p, int frames, double fps,
                          const FieldSource& fields, const FrameSink& sink) {
  validate(p);
  if (frames < 1) throw std::invalid_argument("frames: at least 1");
  if (!(fps > 0.0)) throw std::invalid_argument("fps: > 0");
  TextureSynthesizer synth(photo, p.synth);
  Pcg32 rng(p.seed, 0x7e47);
  AnimateStats st;
  auto key = [&](const FieldFrame& f) {
    const int w = f.temperature.width * p.scale, h = f.temperature.height * p.scale;
    ++st.key_frames;
    return synth.synthesize(temperature_target(f, p.scale), w, h, rng);
  };
  const int K = p.key_interval, m = p.dissolve;
  std::optional<RgbImage> current, next;
  FieldFrame prev;
  for (int f = 0; f < frames; ++f) {
    FieldFrame field = fields(f);
    if (p.independent) {
      sink(f, key(field));
      continue;
    }
    // Carry both chains from frame f-1 to f with the flow at f-1.
    if (current) current = advect_image(*current, prev, p.scale, 1.0 / fps);
    if (next) next = advect_image(*next, prev, p.scale, 1.0 / fps);
    if (!current) {
      current = key(field);
    } else if (m > 0 && (f + m) % K == 0) {
      next = key(field);  // head of the overlap, m frames before the key time
    } else if (m == 0 && f % K == 0) {
      current = key(field);
    }
    RgbImage out = *current;
    if (next) {
      const int start = ((f + m) / K) * K - m;  // frame the overlap began
      const float a = static_cast<float>(f - start) / static_cast<float>(m);
      for (size_t k = 0; k < out.px.size(); ++k)
        out.px[k] = out.px[k] * (1.0f - a) + next->px[k] * a;
      if (f - start == m) {  // the key time: hand over to the new chain
        current = std::move(next);
        next.reset();
      }
    }
    sink(f, out);
    prev = std::move(field);
  }
  return st;
}

Image to_image(const RgbImage& rgb) {
  Image img;
  img.width = rgb.width;
  img.height = rgb.height;
  img.channels = 3;
  img.pixels.resize(rgb.px.size());
  for (size_t k = 0; k < rgb.px.size(); ++k)
    img.pixels[k] = static_cast<uint8_t>(std::lround(std::clamp(rgb.px[k], 0.0f, 1.0f) * 255.0f));
  return img;
}

}  // namespace candela::fluid
