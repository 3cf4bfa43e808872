// The folder `candela-tool simulate` (and `texturize`) writes, which
// `candela-tool ingest` reads as a PNG-frame clip:
//   DIR/manifest.toml                  what is below, and how it was made
//   DIR/frames/frame_000000.png ...    one PNG per frame (gray or RGB)
//   DIR/fields/field_000000.cfld ...   temperature + velocity (simulate only,
//                                      unless --no-fields; see field_file.h)
#pragma once

#include <string>

namespace candela::fluid {

struct SimManifest {
  std::string name = "clip";
  std::string source = "candela-tool simulate";
  std::string command;  // the full command line that made it
  int frames = 0;
  double fps = 30.0;
  int width = 0;  // image size, pixels
  int height = 0;
  std::string colour = "gray";  // "gray" | "blackbody" | "rgb"
  bool has_fields = false;
  int grid_width = 0;  // field size, cells
  int grid_height = 0;
  double t_ambient = 300.0;
  double t_reference = 1900.0;
};

std::string frame_path(const std::string& dir, int index);
std::string field_path(const std::string& dir, int index);
std::string manifest_path(const std::string& dir);

// Atomic write (temporary file + rename). Throws RuntimeError.
void write_manifest(const std::string& dir, const SimManifest& m);
// Throws ConfigError(file, key, expected) on anything missing or malformed.
SimManifest read_manifest(const std::string& dir);

}  // namespace candela::fluid
