// The Beier-Neely feature-line warp (SIGGRAPH '92) on the CPU: the exact
// per-pixel form (backward: each destination pixel finds its source), and
// the paper's fast form, the same formula applied to the vertices of a
// coarse mesh over the still (forward: each vertex finds where it goes),
// which the GPU then texture-maps. gles_shaders/candle_flame.vert runs the
// forward form per vertex; this file is its reference and its test oracle.
#pragma once

#include <functional>
#include <span>
#include <vector>

#include "elements/candle/candle_rig.h"

namespace candela {

struct WarpPoint {
  double x = 0, y = 0;
};
struct WarpLine {
  WarpPoint p, q;
};
struct WarpWeights {
  double a = 0.02;  // keeps weights finite on a line (billboard units)
  double b = 2.0;   // how fast influence falls with distance
  double p = 0.5;   // how much longer lines count more
};

// Where x (in the image of `from`) lands in the image of `to`: each line pair
// maps x by eq. (2); the results are averaged with weights
// (length^p / (a + distance))^b.
WarpPoint beier_neely(WarpPoint x, std::span<const WarpLine> from, std::span<const WarpLine> to,
                      const WarpWeights& w);

std::vector<WarpLine> to_warp_lines(const ControlLines& lines);

// A (cells+1)^2 grid of vertices covering the still, row by row from the
// bottom: x in [-aspect/2, aspect/2], y in [0, 1].
std::vector<WarpPoint> mesh_vertices(int cells, double aspect);
// Two triangles per cell, counter-clockwise, as drawn. With `keep`, only the
// cells keep(i, j) accepts (column i, row j from the bottom).
std::vector<unsigned short> mesh_indices(int cells);
template <typename Keep>
std::vector<unsigned short> mesh_indices(int cells, Keep keep) {
  std::vector<unsigned short> idx;
  const int row = cells + 1;
  for (int j = 0; j < cells; ++j)
    for (int i = 0; i < cells; ++i) {
      if (!keep(i, j)) continue;
      const auto a = static_cast<unsigned short>(j * row + i);
      const auto b = static_cast<unsigned short>(a + 1);
      const auto c = static_cast<unsigned short>(a + row);
      const auto d = static_cast<unsigned short>(c + 1);
      idx.insert(idx.end(), {a, b, d, a, d, c});
    }
  return idx;
}

// The forward (fast) warp: every mesh vertex mapped from the source lines to
// the destination lines.
std::vector<WarpPoint> warp_mesh(std::span<const WarpPoint> vertices,
                                 std::span<const WarpLine> source, std::span<const WarpLine> dest,
                                 const WarpWeights& w);

struct WarpError {
  double max_px = 0;  // worst displacement, in still pixels
  double mean_px = 0;
};
// How far the drawn mesh (triangles, linear inside) puts still pixels from
// where the exact backward warp would fetch them: sampled `samples` times
// per triangle edge, measured in pixels of a still `still_px` high. With
// `visible`, only points of the still it accepts count (errors where the
// still is transparent cannot be seen).
WarpError mesh_warp_error(int cells, double aspect, std::span<const WarpLine> source,
                          std::span<const WarpLine> dest, const WarpWeights& w, double still_px,
                          int samples = 6, const std::function<bool(WarpPoint)>& visible = nullptr);

}  // namespace candela
