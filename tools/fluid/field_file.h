// Per-frame simulation fields on disk: a Candela container file
// (model/model_file.h: JSON header, 64-byte aligned tensors, CRC-32), read by
// the same reader as models and noise tables.
//   tensor "temperature"  F32 [height, width] (K), row 0 = BOTTOM row
//   tensors "u", "v"      F32 [height, width] (cells/s, cell centres,
//                         v > 0 = up), only when "velocity" is true
//   "model" info          {"kind": "fluid-field", "version": 1, "frame": index,
//                          "time": s, "t_ambient": K, "t_reference": K (maps to
//                          full brightness), "velocity": bool}
// Width and height are 1..8192 cells; every value must be finite.
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
// Throws ConfigError(path, field, what was expected) on any defect
// (model::ModelError for the container's framing and checksum).
FieldFrame read_field_file(const std::string& path);

}  // namespace candela::fluid
