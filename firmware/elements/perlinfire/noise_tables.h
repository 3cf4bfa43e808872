// The hash tables behind the fire's noise. As in the Perlin-fire paper, a
// lattice point is hashed through a permutation texture and its gradient
// comes from a fixed gradient table. The tables are built here, without GL,
// from the element's seed, so the shader and the tests' CPU reference read
// exactly the same numbers.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace candela {

// Constants shared by the GLSL noise library (injected as #defines when the
// program is built) and the CPU reference: one place to change them.
struct NoiseConstants {
  // Each simplex corner's kernel is (r2 - |d|^2)^4; 0.5 keeps the noise
  // continuous across simplex boundaries (the common 0.6 does not quite).
  static constexpr double kSimplexRadius2 = 0.5;
  // Scales bringing each noise to about [-1, 1] (measured over many points).
  static constexpr double kSimplex3Scale = 76.0;
  static constexpr double kSimplex4Scale = 62.0;
  static constexpr double kPerlin4Scale = 0.9;
  // The 3-D noise repeats every 768 lattice units along an axis (256 in the
  // skewed lattice times 3), so scroll and drift offsets wrap there seamlessly.
  static constexpr int kPeriod3 = 768;
};

// Perlin's 12 cube-edge gradients padded to 16, and the 32 edges of the 4-cube.
extern const int8_t kGradients3[16][3];
extern const int8_t kGradients4[32][4];

class NoiseTables {
 public:
  static constexpr int kSize = 256;
  explicit NoiseTables(uint64_t seed);

  // perm2(a, b) = perm[(perm[a] + b) & 255]: the 2-D permutation texture.
  uint8_t perm2(int a, int b) const {
    return perm2d_[static_cast<std::size_t>((b & 255) * kSize + (a & 255))];
  }
  // The gradient of 3-D corner (i, j, k) is row k, column perm2(i, j) of grad3:
  // kGradients3[perm2(perm2(i, j), k) & 15]; its 4th component (+-1) is the
  // direction the flow noise spins it.
  const int8_t* grad3(int a, int k) const { return &grad3_[texel(a, k) * 4]; }
  // 4-D corner (i, j, k, l): column perm2(perm2(i, j), k), row l.
  const int8_t* grad4(int b, int l) const { return &grad4_[texel(b, l) * 4]; }

  // Texture data, rows of 256 texels, row y = second argument.
  const std::vector<uint8_t>& perm2d() const { return perm2d_; }    // R8UI
  const std::vector<int8_t>& grad3_rgba() const { return grad3_; }  // RGBA8_SNORM
  const std::vector<int8_t>& grad4_rgba() const { return grad4_; }  // RGBA8_SNORM

 private:
  static std::size_t texel(int a, int b) {
    return static_cast<std::size_t>((b & 255) * kSize + (a & 255));
  }
  std::array<uint8_t, kSize> perm_{};
  std::vector<uint8_t> perm2d_;
  std::vector<int8_t> grad3_, grad4_;
};

}  // namespace candela
