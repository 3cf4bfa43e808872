// The candle's wax body as one mesh, drawn once per candle: the side, the
// melted top with a raised rim and a pool, and the wick.
#pragma once

#include <vector>

namespace candela {

constexpr float kPoolDepth = 0.15f;  // melt pool depth, in radii

// Per vertex: (x, z on a unit circle scaled by the ring's radius, y parameter,
// kind) and a normal: 7 floats. Kind 0: side (y = fraction of height); 1: top
// (y = offset in radii from the top edge); 2: wick (y = fraction of its length).
struct BodyMesh {
  std::vector<float> vertices;  // 7 floats each
  std::vector<unsigned short> indices;
};
BodyMesh make_body_mesh(int segments, int wick_segments);

}  // namespace candela
