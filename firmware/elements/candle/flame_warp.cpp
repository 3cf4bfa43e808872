#include "elements/candle/flame_warp.h"

#include <algorithm>
#include <cmath>

namespace candela {

WarpPoint beier_neely(WarpPoint x, std::span<const WarpLine> from, std::span<const WarpLine> to,
                      const WarpWeights& w) {
  double sx = 0, sy = 0, sw = 0;
  for (size_t i = 0; i < from.size() && i < to.size(); ++i) {
    const WarpLine& a = from[i];
    const WarpLine& b = to[i];
    const double dx = a.q.x - a.p.x, dy = a.q.y - a.p.y;
    const double len2 = dx * dx + dy * dy;
    if (len2 <= 1e-18) continue;
    const double len = std::sqrt(len2);
    const double ex = x.x - a.p.x, ey = x.y - a.p.y;
    // Eq. (2): u along the line (0..1 on it), v the signed distance across.
    const double u = (ex * dx + ey * dy) / len2;
    const double v = (ex * -dy + ey * dx) / len;
    const double bx = b.q.x - b.p.x, by = b.q.y - b.p.y;
    const double blen = std::sqrt(bx * bx + by * by);
    double mx = b.p.x + u * bx, my = b.p.y + u * by;
    if (blen > 1e-9) {
      mx += v * -by / blen;
      my += v * bx / blen;
    }
    double dist;
    if (u < 0)
      dist = std::sqrt(ex * ex + ey * ey);
    else if (u > 1)
      dist = std::hypot(x.x - a.q.x, x.y - a.q.y);
    else
      dist = std::abs(v);
    const double weight = std::pow(std::pow(len, w.p) / (w.a + dist), w.b);
    sx += mx * weight;
    sy += my * weight;
    sw += weight;
  }
  if (sw <= 0) return x;
  return {sx / sw, sy / sw};
}

std::vector<WarpLine> to_warp_lines(const ControlLines& lines) {
  std::vector<WarpLine> out;
  for (int i = 0; i < lines.count; ++i) {
    const ControlLine& l = lines.line[i];
    out.push_back({{l.px.to_double(), l.py.to_double()}, {l.qx.to_double(), l.qy.to_double()}});
  }
  return out;
}

std::vector<WarpPoint> mesh_vertices(int cells, double aspect) {
  std::vector<WarpPoint> v;
  for (int j = 0; j <= cells; ++j)
    for (int i = 0; i <= cells; ++i)
      v.push_back(
          {(static_cast<double>(i) / cells - 0.5) * aspect, static_cast<double>(j) / cells});
  return v;
}

std::vector<unsigned short> mesh_indices(int cells) {
  return mesh_indices(cells, [](int, int) { return true; });
}

std::vector<WarpPoint> warp_mesh(std::span<const WarpPoint> vertices,
                                 std::span<const WarpLine> source, std::span<const WarpLine> dest,
                                 const WarpWeights& w) {
  std::vector<WarpPoint> out(vertices.size());
  for (size_t i = 0; i < vertices.size(); ++i) out[i] = beier_neely(vertices[i], source, dest, w);
  return out;
}

WarpError mesh_warp_error(int cells, double aspect, std::span<const WarpLine> source,
                          std::span<const WarpLine> dest, const WarpWeights& w, double still_px,
                          int samples, const std::function<bool(WarpPoint)>& visible) {
  const auto src = mesh_vertices(cells, aspect);
  const auto dst = warp_mesh(src, source, dest, w);
  const auto idx = mesh_indices(cells);
  WarpError e;
  double sum = 0;
  long count = 0;
  for (size_t t = 0; t + 2 < idx.size(); t += 3) {
    for (int i = 0; i <= samples; ++i)
      for (int j = 0; i + j <= samples; ++j) {
        const double l1 = static_cast<double>(i) / samples, l2 = static_cast<double>(j) / samples;
        const double l0 = 1 - l1 - l2;
        const WarpPoint& s0 = src[idx[t]];
        const WarpPoint& s1 = src[idx[t + 1]];
        const WarpPoint& s2 = src[idx[t + 2]];
        const WarpPoint& d0 = dst[idx[t]];
        const WarpPoint& d1 = dst[idx[t + 1]];
        const WarpPoint& d2 = dst[idx[t + 2]];
        // The drawn triangle shows the still at s here, at screen point d.
        const WarpPoint s{l0 * s0.x + l1 * s1.x + l2 * s2.x, l0 * s0.y + l1 * s1.y + l2 * s2.y};
        if (visible && !visible(s)) continue;
        const WarpPoint d{l0 * d0.x + l1 * d1.x + l2 * d2.x, l0 * d0.y + l1 * d1.y + l2 * d2.y};
        // The exact warp fetches the still at `exact` for that point.
        const WarpPoint exact = beier_neely(d, dest, source, w);
        const double err = std::hypot(exact.x - s.x, exact.y - s.y) * still_px;
        e.max_px = std::max(e.max_px, err);
        sum += err;
        ++count;
      }
  }
  e.mean_px = count ? sum / count : 0;
  return e;
}

}  // namespace candela
