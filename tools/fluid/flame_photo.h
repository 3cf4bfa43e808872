// A procedurally rendered "photograph" of a flame (RGBA, transparent
// background), so the texture-synthesis tests and recipes never need real
// footage: a teardrop of fire whose brightness and colour carry several
// octaves of seeded, vertically stretched value noise (the detail the
// synthesis copies).
#pragma once

#include <cstdint>

#include "core/image.h"

namespace candela::fluid {

// Throws std::invalid_argument for sizes outside 16..4096.
Image render_flame_photo(int width, int height, uint64_t seed, bool with_alpha = true);

}  // namespace candela::fluid
