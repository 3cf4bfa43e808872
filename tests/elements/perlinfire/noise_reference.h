// A CPU reference of the fire's noise: the same algorithms as
// gles_shaders/perlinfire_noise.frag (simplex 3-D, 3-D flow, 4-D, classic
// 4-D Perlin), written again in double precision over the same NoiseTables,
// so the tests can hold the GPU's values against it.
#pragma once

#include "elements/perlinfire/noise_tables.h"

namespace candela::test {

struct P3 {
  double x, y, z;
};
struct P4 {
  double x, y, z, w;
};

class NoiseReference {
 public:
  explicit NoiseReference(const NoiseTables& tables) : t_(tables) {}
  double simplex3(P3 p) const { return simplex3_flow(p, 0.0, false); }
  // Gradients spun about y by +-angle (the direction each corner's table entry says).
  double simplex3_flow(P3 p, double angle, bool flow = true) const;
  double simplex4(P4 p) const;
  double perlin4(P4 p) const;

 private:
  const NoiseTables& t_;
};

}  // namespace candela::test
