// The head of a test scene: a black room and a camera. The render tests
// write the elements they test after it.
#pragma once

#include <cstdio>
#include <string>

namespace candela::test {

// "[background]" black and "[camera]" at (x, y, z) looking at (tx, ty, tz)
// with a vertical field of view of fov degrees.
inline std::string black_room(double x, double y, double z, double tx, double ty, double tz,
                              double fov) {
  char text[256];
  std::snprintf(text, sizeof text,
                "\n[background]\ncolor = \"#000000\"\n[camera]\nposition = [%g, %g, %g]\n"
                "target = [%g, %g, %g]\nfov = %g\n",
                x, y, z, tx, ty, tz, fov);
  return text;
}

// A built-in scene's text without one of its tables (e.g. a fireplace
// without "[element.firebox]": measuring the fire, not the lit bricks), up
// to the blank line that ends it. Empty when the scene has no such table.
inline std::string without_table(std::string toml, const std::string& header) {
  const auto at = toml.find(header);
  if (at == std::string::npos) return {};
  toml.erase(at, toml.find("\n\n", at) - at);
  return toml;
}

}  // namespace candela::test
