// The fire's profile: a 2-D picture of half a flame (left edge = the axis,
// right edge = the volume's rim, top row = the top of the volume) whose RGB
// is the colour and A the density. Swept about the vertical axis it gives the
// fire its shape. Users may supply their own PNG; the default is drawn here in
// code (never taken from footage).
#pragma once

#include <string>

#include "core/image.h"

namespace candela {

// A flame: white-yellow core at the base, orange and red towards its rim and
// tip, fading to nothing at the rim, at the top row and outside the tongue.
// `base_width`: the flame's half-width at its base (1 = the rim); `taper`: how
// its width falls towards the tip (smaller: flatter topped, a wall of flame);
// `tip`: the tip's height (1 = the volume's top).
Image make_default_fire_profile(int width = 64, int height = 128, double base_width = 0.8,
                                double taper = 0.65, double tip = 0.92);

// Reads a profile PNG as RGBA. Throws ConfigError naming the file and the key
// when it cannot be used (too small; density not fading to zero at the rim).
Image load_fire_profile(const std::string& path, const std::string& scene_file,
                        const std::string& key);

}  // namespace candela
