#include "elements/perlinfire/noise_reference.h"

#include <algorithm>
#include <cmath>

namespace candela::test {
namespace {

using C = NoiseConstants;

double kernel(double d2) {
  const double t = std::max(C::kSimplexRadius2 - d2, 0.0);
  return t * t * t * t;
}
int wrap(double i) { return static_cast<int>(i - 256.0 * std::floor(i / 256.0)); }
double step(double edge, double x) { return x < edge ? 0.0 : 1.0; }
double snorm(int8_t v) { return std::max(v / 127.0, -1.0); }

}  // namespace

double NoiseReference::simplex3_flow(P3 p, double angle, bool flow) const {
  const double f3 = 1.0 / 3.0, g3 = 1.0 / 6.0;
  const double s = (p.x + p.y + p.z) * f3;
  const double i[3] = {std::floor(p.x + s), std::floor(p.y + s), std::floor(p.z + s)};
  const double t = (i[0] + i[1] + i[2]) * g3;
  const double x0[3] = {p.x - (i[0] - t), p.y - (i[1] - t), p.z - (i[2] - t)};
  // Which simplex of the skewed cube: order the offsets (ties as the shader's step()).
  const double g[3] = {step(x0[1], x0[0]), step(x0[2], x0[1]), step(x0[0], x0[2])};
  const double l[3] = {1 - g[0], 1 - g[1], 1 - g[2]};
  const double i1[3] = {std::min(g[0], l[2]), std::min(g[1], l[0]), std::min(g[2], l[1])};
  const double i2[3] = {std::max(g[0], l[2]), std::max(g[1], l[0]), std::max(g[2], l[1])};
  const double off[4][3] = {{0, 0, 0}, {i1[0], i1[1], i1[2]}, {i2[0], i2[1], i2[2]}, {1, 1, 1}};
  const int c[3] = {wrap(i[0]), wrap(i[1]), wrap(i[2])};
  const double cs = std::cos(angle), sn = std::sin(angle);
  double n = 0;
  for (int k = 0; k < 4; ++k) {
    double d[3];
    for (int a = 0; a < 3; ++a) d[a] = x0[a] - off[k][a] + k * g3;
    const int8_t* gr =
        t_.grad3(t_.perm2(c[0] + static_cast<int>(off[k][0]), c[1] + static_cast<int>(off[k][1])),
                 c[2] + static_cast<int>(off[k][2]));
    double gx = snorm(gr[0]), gy = snorm(gr[1]), gz = snorm(gr[2]);
    if (flow) {
      const double s2 = sn * snorm(gr[3]);
      const double rx = gx * cs + gz * s2, rz = -gx * s2 + gz * cs;
      gx = rx;
      gz = rz;
    }
    n += kernel(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) * (gx * d[0] + gy * d[1] + gz * d[2]);
  }
  return C::kSimplex3Scale * n;
}

double NoiseReference::simplex4(P4 p) const {
  const double f4 = (std::sqrt(5.0) - 1.0) / 4.0, g4 = (5.0 - std::sqrt(5.0)) / 20.0;
  const double v[4] = {p.x, p.y, p.z, p.w};
  const double s = (v[0] + v[1] + v[2] + v[3]) * f4;
  double i[4], x0[4];
  for (int a = 0; a < 4; ++a) i[a] = std::floor(v[a] + s);
  const double t = (i[0] + i[1] + i[2] + i[3]) * g4;
  for (int a = 0; a < 4; ++a) x0[a] = v[a] - (i[a] - t);
  // Rank of each axis among the four offsets (how many it is >= to).
  double rank[4] = {0, 0, 0, 0};
  for (int a = 0; a < 4; ++a)
    for (int b = a + 1; b < 4; ++b) {
      const double ge = step(x0[b], x0[a]);  // x0[a] >= x0[b]
      rank[a] += ge;
      rank[b] += 1 - ge;
    }
  double off[5][4];
  for (int a = 0; a < 4; ++a) {
    off[0][a] = 0;
    off[1][a] = std::clamp(rank[a] - 2, 0.0, 1.0);
    off[2][a] = std::clamp(rank[a] - 1, 0.0, 1.0);
    off[3][a] = std::clamp(rank[a], 0.0, 1.0);
    off[4][a] = 1;
  }
  int c[4];
  for (int a = 0; a < 4; ++a) c[a] = wrap(i[a]);
  double n = 0;
  for (int k = 0; k < 5; ++k) {
    double d[4], d2 = 0;
    int q[4];
    for (int a = 0; a < 4; ++a) {
      d[a] = x0[a] - off[k][a] + k * g4;
      d2 += d[a] * d[a];
      q[a] = c[a] + static_cast<int>(off[k][a]);
    }
    const int8_t* gr = t_.grad4(t_.perm2(t_.perm2(q[0], q[1]), q[2]), q[3]);
    double dot = 0;
    for (int a = 0; a < 4; ++a) dot += snorm(gr[a]) * d[a];
    n += kernel(d2) * dot;
  }
  return C::kSimplex4Scale * n;
}

double NoiseReference::perlin4(P4 p) const {
  const double v[4] = {p.x, p.y, p.z, p.w};
  double f[4], u[4];
  int c[4];
  for (int a = 0; a < 4; ++a) {
    const double i = std::floor(v[a]);
    f[a] = v[a] - i;
    u[a] = f[a] * f[a] * f[a] * (f[a] * (f[a] * 6 - 15) + 10);
    c[a] = wrap(i);
  }
  // The 16 corners of the hypercube, interpolated one axis at a time.
  double n[16];
  for (int b = 0; b < 16; ++b) {
    int q[4];
    double dot = 0;
    const int8_t* gr = nullptr;
    for (int a = 0; a < 4; ++a) q[a] = c[a] + ((b >> a) & 1);
    gr = t_.grad4(t_.perm2(t_.perm2(q[0], q[1]), q[2]), q[3]);
    for (int a = 0; a < 4; ++a) dot += snorm(gr[a]) * (f[a] - ((b >> a) & 1));
    n[b] = dot;
  }
  for (int a = 0, len = 16; a < 4; ++a, len /= 2)
    for (int b = 0; b < len / 2; ++b) n[b] = n[2 * b] + u[a] * (n[2 * b + 1] - n[2 * b]);
  return C::kPerlin4Scale * n[0];
}

}  // namespace candela::test
