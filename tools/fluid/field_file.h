// Per-frame simulation fields on disk ("CFLD" version 1), little-endian:
//   offset  0  char[4]  "CFLD"
//           4  uint32   version (1)
//           8  uint32   width  (cells, 1..8192)
//          12  uint32   height (cells, 1..8192)
//          16  uint32   frame index
//          20  uint32   flags (bit 0: velocity follows the temperature)
//          24  float64  time (s)
//          32  float64  ambient temperature (K)
//          40  float64  reference temperature (K): maps to full brightness
//          48  float32  temperature[width*height] (K), row 0 = BOTTOM row
//          ..  float32  u[width*height], v[width*height] (cells/s, cell
//                       centres, v > 0 = up), only when flags bit 0 is set
// The file size must match exactly; every value must be finite.
#pragma once

#include <cstdint>
#include <string>

#include "grid2.h"

namespace candela::fluid {

struct FieldFrame {
  uint32_t index = 0;
  double time = 0.0;
  double t_ambient = 300.0;
  double t_reference = 1900.0;
  Grid2 temperature;
  bool has_velocity = false;
  Grid2 u, v;  // cell-centred
};

// Atomic (temporary file + rename). Throws RuntimeError when it cannot write.
void write_field_file(const std::string& path, const FieldFrame& frame);
// Throws ConfigError(path, field, what was expected) on any defect.
FieldFrame read_field_file(const std::string& path);

}  // namespace candela::fluid
