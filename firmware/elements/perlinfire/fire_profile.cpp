#include "elements/perlinfire/fire_profile.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace candela {
namespace {

double smoothstep(double e0, double e1, double x) {
  const double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
  return t * t * (3 - 2 * t);
}

// Heat (0..1) to colour: dark red, orange, yellow, near white.
void heat_colour(double h, double rgb[3]) {
  rgb[0] = std::clamp(h * 2.2, 0.0, 1.0);
  rgb[1] = std::clamp((h - 0.25) * 1.6, 0.0, 1.0);
  rgb[2] = std::clamp((h - 0.7) * 2.0, 0.0, 1.0);
}

uint8_t to_byte(double v) {
  return static_cast<uint8_t>(std::lround(std::clamp(v, 0.0, 1.0) * 255));
}

}  // namespace

Image make_default_fire_profile(int width, int height, double base_width, double taper,
                                double tip) {
  Image img;
  img.width = width;
  img.height = height;
  img.channels = 4;
  img.pixels.assign(static_cast<size_t>(width) * height * 4, 0);
  for (int row = 0; row < height; ++row) {
    // v: height in the volume, 0 at the bottom row.
    const double v = 1.0 - (row + 0.5) / height;
    // Half-width of the flame at this height: a broad base narrowing to a tip
    // below the top of the volume, so displaced lookups find empty space.
    const double half_width = base_width * std::pow(std::max(0.0, 1.0 - v / tip), taper);
    for (int col = 0; col < width; ++col) {
      const double r = (col + 0.5) / width;
      uint8_t* px = img.row(row) + col * 4;
      if (half_width <= 0 || row == 0 || col == width - 1) continue;  // the rim stays empty
      // Density falls linearly from the axis to the rim at this height (and
      // towards the top): a field whose level sets are nested flame outlines,
      // so the sheets' threshold (perlinfire.frag) cuts one clean outline and
      // the noise, moving lookups, tears it into tongues.
      const double inside = 1.0 - r / half_width;
      if (inside <= 0) continue;
      const double core = 1.0 - std::min(1.0, r / half_width);
      const double heat = std::clamp((1.0 - v) * 0.85 * (0.45 + 0.55 * core) + 0.12, 0.0, 1.0);
      double rgb[3];
      heat_colour(heat, rgb);
      const double density =
          std::min(1.0, inside * 1.4) * (0.45 + 0.55 * smoothstep(0.0, 0.85, 1.0 - v));
      // Straight (not premultiplied) alpha, as a PNG stores it.
      px[0] = to_byte(rgb[0]);
      px[1] = to_byte(rgb[1]);
      px[2] = to_byte(rgb[2]);
      px[3] = to_byte(density);
    }
  }
  return img;
}

Image load_fire_profile(const std::string& path, const std::string& scene_file,
                        const std::string& key) {
  Image img;
  try {
    img = read_png(path, 4);
  } catch (const ConfigError& e) {  // name the scene and key too, as every scene error does
    throw ConfigError(scene_file, key, std::string("expected a profile PNG: ") + e.what());
  }
  if (img.width < 4 || img.height < 4)
    throw ConfigError(scene_file, key,
                      "expected a profile PNG of at least 4x4 pixels, got '" + path + "' (" +
                          std::to_string(img.width) + "x" + std::to_string(img.height) + ")");
  // The texture is clamped at its edges, so a dense rim would fill the whole box.
  int dense = 0;
  for (int y = 0; y < img.height; ++y) dense += img.at(img.width - 1, y, 3) > 8;
  for (int x = 0; x < img.width; ++x) dense += img.at(x, 0, 3) > 8;
  if (dense > 0)
    throw ConfigError(scene_file, key,
                      "expected a profile PNG whose right column and top row are transparent "
                      "(alpha 0: outside the flame), but '" +
                          path + "' has " + std::to_string(dense) + " dense pixels there");
  return img;
}

}  // namespace candela
