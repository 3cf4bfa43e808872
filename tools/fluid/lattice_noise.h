// Hash noise on an integer lattice: a value is a function of the lattice
// point and the seed (not a random stream), so it does not depend on the
// order cells or pixels are visited in. Shared by the solver's turbulent
// injection and the fuel bed's textures.
#pragma once

#include <cstdint>

namespace candela::fluid {

uint64_t mix64(uint64_t z);
// Uniform in [0, 1) for a lattice point.
double lattice_hash(uint64_t seed, int64_t i, int64_t j, int64_t k);
// Value noise in [0, 1] in (x, y, t), smoothstep-blended between lattice points.
double value_noise(uint64_t seed, double x, double y, double t);
// Pink (1/f) noise of time t (seconds): six equal octaves of value noise
// from 0.75 to 24 Hz; mean about 0, std about 1.
double pink_flicker(uint64_t seed, double t);

}  // namespace candela::fluid
