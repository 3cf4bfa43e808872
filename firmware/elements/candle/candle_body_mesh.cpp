#include "elements/candle/candle_body_mesh.h"

#include <algorithm>
#include <cmath>
#include <iterator>

namespace candela {
namespace {
constexpr float kPi = 3.14159265358979f;
}  // namespace

BodyMesh make_body_mesh(int segments, int wick_segments) {
  BodyMesh m;
  auto ring = [&](int n, float rad, float y, float kind, float nx_scale, float ny) {
    const auto first = static_cast<unsigned short>(m.vertices.size() / 7);
    for (int i = 0; i <= n; ++i) {
      const float a = 2 * kPi * static_cast<float>(i) / n;
      const float c = std::cos(a), s = std::sin(a);
      m.vertices.insert(m.vertices.end(),
                        {c * rad, s * rad, y, kind, c * nx_scale, ny, s * nx_scale});
    }
    return first;
  };
  // Counter-clockwise seen from outside/above, so back faces can be culled.
  auto strip = [&](int n, unsigned short lower, unsigned short upper) {
    for (int i = 0; i < n; ++i) {
      const auto a0 = static_cast<unsigned short>(lower + i);
      const auto a1 = static_cast<unsigned short>(lower + i + 1);
      const auto b0 = static_cast<unsigned short>(upper + i);
      const auto b1 = static_cast<unsigned short>(upper + i + 1);
      m.indices.insert(m.indices.end(), {a0, b0, a1, a1, b0, b1});
    }
  };
  // Side.
  const auto s0 = ring(segments, 1.0f, 0.0f, 0, 1, 0);
  const auto s1 = ring(segments, 1.0f, 1.0f, 0, 1, 0);
  strip(segments, s0, s1);
  // Melted top, outside in (radius factor, offset in radii, normal's
  // outward tilt): the rim's lip, its inner slope, the pool and its middle.
  const float profile[][3] = {{1.0f, 0.0f, 0.9f}, {0.95f, 0.05f, 0.1f}, {0.8f, -0.1f, -0.45f}};
  unsigned short prev = ring(segments, profile[0][0], profile[0][1], 1, profile[0][2], 0.45f);
  for (size_t k = 1; k < std::size(profile); ++k) {
    const float t = profile[k][2];
    const float ny = std::sqrt(std::max(0.0f, 1 - t * t));
    const auto cur = ring(segments, profile[k][0], profile[k][1], 1, t, ny);
    // Going inward the "upper" ring is the inner one.
    strip(segments, prev, cur);
    prev = cur;
  }
  // The pool's middle: a fan.
  const auto centre = static_cast<unsigned short>(m.vertices.size() / 7);
  m.vertices.insert(m.vertices.end(), {0, 0, -kPoolDepth, 1, 0, 1, 0});
  for (int i = 0; i < segments; ++i)
    m.indices.insert(m.indices.end(), {static_cast<unsigned short>(prev + i), centre,
                                       static_cast<unsigned short>(prev + i + 1)});
  // Wick: a thin cylinder from the pool up.
  const auto w0 = ring(wick_segments, 1.0f, 0.0f, 2, 1, 0);
  const auto w1 = ring(wick_segments, 1.0f, 1.0f, 2, 1, 0);
  strip(wick_segments, w0, w1);
  return m;
}

}  // namespace candela
