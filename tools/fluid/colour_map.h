// Temperature -> pixels. Gray is the normalised excess temperature
// s = (T - T_amb) / (T_ref - T_amb), clamped to 0..1. Black-body colours the
// same brightness with the chromaticity of a Planck radiator at T (CIE 1931
// matching functions, multi-lobe fit of Wyman, Sloan and Shirley 2013, to
// linear sRGB, then the sRGB transfer curve).
#pragma once

#include <array>
#include <cstdint>

#include "core/image.h"
#include "grid2.h"

namespace candela::fluid {

enum class ColourMode { kGray, kBlackBody };

// Linear-sRGB chromaticity of a black body at `kelvin`, scaled so the largest
// channel is 1.
std::array<double, 3> black_body_rgb(double kelvin);

// Renders the temperature grid (row 0 = bottom) as an image scale times as
// large (bilinear), rows top-down. Gray: 1 channel; black-body: 3 channels.
Image render_temperature(const Grid2& temperature, double t_ambient, double t_reference,
                         ColourMode mode, int scale);

}  // namespace candela::fluid
