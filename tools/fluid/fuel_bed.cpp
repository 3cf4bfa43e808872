#include "fuel_bed.h"

#include <algorithm>
#include <cmath>

#include "lattice_noise.h"

namespace candela::fluid {
namespace {

double smoothstep(double a, double b, double x) {
  const double t = std::clamp((x - a) / (b - a), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

// Cellular (Worley) noise: distances to the nearest and second-nearest of
// one seeded point per lattice cell, and the nearest one's cell hash. Their
// difference is small on the net of lines between cells: cracks in char,
// gaps between coals.
struct Cells {
  double f1, f2, id;
};
Cells cells(uint64_t seed, double x, double y) {
  const double fx = std::floor(x), fy = std::floor(y);
  Cells c{9.0, 9.0, 0.0};
  for (int dj = -1; dj <= 1; ++dj)
    for (int di = -1; di <= 1; ++di) {
      const auto i = static_cast<int64_t>(fx) + di, j = static_cast<int64_t>(fy) + dj;
      const double px = i + lattice_hash(seed, i, j, 1), py = j + lattice_hash(seed, i, j, 2);
      const double d = std::hypot(px - x, py - y);
      if (d < c.f1) {
        c.f2 = c.f1;
        c.f1 = d;
        c.id = lattice_hash(seed, i, j, 3);
      } else if (d < c.f2) {
        c.f2 = d;
      }
    }
  return c;
}

// Where a pixel lies on a log: coverage (antialiased), position along it
// (pixels) and across it (-1 bottom .. +1 top, as the camera sees it).
struct OnLog {
  double cover = 0.0, along = 0.0, up = 0.0;
};
OnLog on_log(const Log& l, double x, double y) {
  const double ax = l.x1 - l.x0, ay = l.y1 - l.y0;
  const double len = std::max(1e-9, std::hypot(ax, ay));
  const double t = std::clamp(((x - l.x0) * ax + (y - l.y0) * ay) / (len * len), 0.0, 1.0);
  const double cx = l.x0 + t * ax, cy = l.y0 + t * ay;
  const double dx = x - cx, dy = y - cy;
  OnLog o;
  o.cover = std::clamp(l.radius - std::hypot(dx, dy) + 0.5, 0.0, 1.0);
  o.along = t * len;
  // Rows run top-down: up is -y, turned with the log.
  o.up = std::clamp(-(dy * ax - dx * ay) / len / l.radius, -1.0, 1.0);
  if (ax < 0) o.up = -o.up;
  return o;
}

// A log's surface: bark lit from above by the flames (`light`), and the
// glowing net of cracks where it has charred.
double wood(const FuelBed& bed, const OnLog& o, uint64_t grain, double light, double time) {
  const uint64_t seed = mix64(bed.seed * 0x9e37ull + grain);
  // A cylinder seen side-on: the top faces the flames, the bottom is in shadow.
  const double diffuse = std::pow(std::clamp(0.15 + 0.85 * o.up, 0.0, 1.0), 2.0);
  const double streaks = 0.55 + 0.9 * value_noise(seed, o.along / 16.0, o.up * 3.0, 0.0);
  double v = light * bed.light * 0.15 * diffuse * streaks;
  // Char: glowing cracks, in patches that come and go slowly.
  const Cells c = cells(seed ^ 0xc4a7ull, o.along / 7.0, (o.up + 1.0) * 2.2);
  const double crack = 1.0 - smoothstep(0.0, 0.07, c.f2 - c.f1);
  const double patch = smoothstep(
      0.58, 0.78, value_noise(seed ^ 0x9a7cull, o.along / 30.0, o.up * 0.8, time * 0.35));
  const double pulse = 0.55 + 0.45 * value_noise(seed ^ 0x1f3ull, o.along / 12.0, o.up, time * 1.3);
  v += bed.char_glow * crack * patch * pulse * (0.5 + 0.5 * std::min(1.0, light));
  return v;
}

}  // namespace

FuelBed hearth_fuel_bed(int width, int height, uint64_t seed, bool back_logs) {
  FuelBed b;
  b.seed = seed;
  const double w = width, h = height;
  b.logs = {
      // Two logs behind the flames, then the long one across the front.
      Log{0.08 * w, 0.80 * h, 0.56 * w, 0.75 * h, 0.045 * h, false, 0},
      Log{0.44 * w, 0.74 * h, 0.93 * w, 0.79 * h, 0.045 * h, false, 1},
      Log{0.02 * w, 0.865 * h, 0.98 * w, 0.895 * h, 0.062 * h, true, 2},
  };
  if (!back_logs) b.logs.erase(b.logs.begin(), b.logs.begin() + 2);
  b.coal_top = 0.9 * h;
  b.coal_size = std::max(3.0, 0.04 * h);
  return b;
}

void draw_fuel_bed(const FuelBed& bed, double time, int width, int height,
                   std::vector<float>& canvas) {
  canvas.resize(static_cast<size_t>(width) * height, 0.0f);
  // The flames' light on the wood below them: each column's mean flame
  // light, spread sideways (a fire lights more than what is right under it).
  std::vector<double> column(width, 0.0), light(width, 0.0);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) column[x] += canvas[static_cast<size_t>(y) * width + x];
  const int spread = std::max(1, width / 8);
  for (int x = 0; x < width; ++x) {
    double s = 0.0;
    int n = 0;
    for (int k = std::max(0, x - spread); k <= std::min(width - 1, x + spread); ++k, ++n)
      s += column[k];
    light[x] = 6.0 * s / (n * static_cast<double>(height));
  }
  const uint64_t coal_seed = mix64(bed.seed ^ 0xc0a1ull);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const double px = x + 0.5, py = y + 0.5;
      // Coals: dark lumps, a few of them glowing from inside, pulsing.
      double base = 0.0;
      if (bed.coal_top > 0.0 && py > bed.coal_top - bed.coal_size) {
        const Cells c = cells(coal_seed, px / bed.coal_size, py / (0.6 * bed.coal_size));
        const double lump = smoothstep(0.04, 0.3, c.f2 - c.f1);
        const double hot = smoothstep(0.55, 0.95, c.id) * (1.0 - smoothstep(0.1, 0.6, c.f1));
        const double pulse = 0.4 + 0.6 * value_noise(coal_seed ^ 0x5ull, px / (3 * bed.coal_size),
                                                     py / bed.coal_size, time * 0.9 + 7.0 * c.id);
        const double lit = 0.03 * light[x] * bed.light;  // the crust, lit by the flames
        base = lump * (lit + bed.coal_glow * hot * pulse) *
               smoothstep(bed.coal_top - bed.coal_size, bed.coal_top, py);
      }
      float& v = canvas[static_cast<size_t>(y) * width + x];
      double flame = v;
      for (size_t i = 0; i < bed.logs.size(); ++i) {
        if (bed.logs[i].in_front) continue;
        const OnLog o = on_log(bed.logs[i], px, py);
        if (o.cover > 0.0)
          base += (wood(bed, o, bed.logs[i].grain, light[x], time) - base) * o.cover;
      }
      double out = base + flame;
      for (size_t i = 0; i < bed.logs.size(); ++i) {
        if (!bed.logs[i].in_front) continue;
        const OnLog o = on_log(bed.logs[i], px, py);
        if (o.cover > 0.0) out += (wood(bed, o, bed.logs[i].grain, light[x], time) - out) * o.cover;
      }
      v = static_cast<float>(out);
    }
}

}  // namespace candela::fluid
