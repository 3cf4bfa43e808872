#include "elements/perlinfire/noise_tables.h"

#include <utility>

#include "core/random.h"

namespace candela {

const int8_t kGradients3[16][3] = {
    {1, 1, 0}, {-1, 1, 0}, {1, -1, 0}, {-1, -1, 0}, {1, 0, 1}, {-1, 0, 1}, {1, 0, -1}, {-1, 0, -1},
    {0, 1, 1}, {0, -1, 1}, {0, 1, -1}, {0, -1, -1}, {1, 1, 0}, {-1, 1, 0}, {0, -1, 1}, {0, -1, -1},
};

const int8_t kGradients4[32][4] = {
    {0, 1, 1, 1},    {0, 1, 1, -1},   {0, 1, -1, 1},   {0, 1, -1, -1},  {0, -1, 1, 1},
    {0, -1, 1, -1},  {0, -1, -1, 1},  {0, -1, -1, -1}, {1, 0, 1, 1},    {1, 0, 1, -1},
    {1, 0, -1, 1},   {1, 0, -1, -1},  {-1, 0, 1, 1},   {-1, 0, 1, -1},  {-1, 0, -1, 1},
    {-1, 0, -1, -1}, {1, 1, 0, 1},    {1, 1, 0, -1},   {1, -1, 0, 1},   {1, -1, 0, -1},
    {-1, 1, 0, 1},   {-1, 1, 0, -1},  {-1, -1, 0, 1},  {-1, -1, 0, -1}, {1, 1, 1, 0},
    {1, 1, -1, 0},   {1, -1, 1, 0},   {1, -1, -1, 0},  {-1, 1, 1, 0},   {-1, 1, -1, 0},
    {-1, -1, 1, 0},  {-1, -1, -1, 0},
};

NoiseTables::NoiseTables(uint64_t seed)
    : perm2d_(kSize * kSize), grad3_(kSize * kSize * 4), grad4_(kSize * kSize * 4) {
  // A seeded Fisher-Yates shuffle: the seed picks the fire's whole noise field.
  Pcg32 rng(seed, 0x7065726CULL);
  for (int i = 0; i < kSize; ++i) perm_[static_cast<std::size_t>(i)] = static_cast<uint8_t>(i);
  for (int i = kSize - 1; i > 0; --i) {
    const uint32_t j = rng.below(static_cast<uint32_t>(i + 1));
    std::swap(perm_[static_cast<std::size_t>(i)], perm_[j]);
  }
  for (int b = 0; b < kSize; ++b)
    for (int a = 0; a < kSize; ++a)
      perm2d_[texel(a, b)] = perm_[(perm_[static_cast<std::size_t>(a)] + b) & 255];
  // 127 is exactly 1.0 in an SNORM texture, so the shader sees the integers.
  for (int b = 0; b < kSize; ++b)
    for (int a = 0; a < kSize; ++a) {
      const uint8_t h = perm2(a, b);
      int8_t* g3 = &grad3_[texel(a, b) * 4];
      for (int c = 0; c < 3; ++c) g3[c] = static_cast<int8_t>(127 * kGradients3[h & 15][c]);
      g3[3] = (h & 16) ? 127 : -127;
      int8_t* g4 = &grad4_[texel(a, b) * 4];
      for (int c = 0; c < 4; ++c) g4[c] = static_cast<int8_t>(127 * kGradients4[h & 31][c]);
    }
}

}  // namespace candela
