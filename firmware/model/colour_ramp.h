// How an eigen-flame's gray becomes colour: one ramp for the runtime (the
// renderer's ramp texture), the studio and candela-tool's renders, so a
// story rendered to mp4 has the colours the kiosk shows. No GL here.
#pragma once

#include <array>
#include <cstdint>
#include <limits>

namespace candela {

// The HLS colour ramp (fixed hue and saturation), as the EigenFires paper
// colours its flames, with each gray's lightness chosen so that the colour's
// luma equals the gray (the paper takes gray as the lightness, which darkens
// an orange flame's edges and core). Gray at or below `black` (0..255) is
// black: it hides the faint reconstruction noise around the flame.
// `hue_top_deg` (NaN: the same hue throughout) is the hue at full brightness;
// the hue moves to it with the cube of the gray, as real fires' colour does
// (measured on the shared fire clips: about 15 degrees, deep orange, up to mid
// gray, then up to about 50, yellow, where the picture nears white).
std::array<uint8_t, 256 * 4> hls_ramp(float hue_deg, float saturation, float black = 0,
                                      float hue_top_deg = std::numeric_limits<float>::quiet_NaN());
// The lightness (0..1) of ramp entry `i` above `black` (0..255).
double ramp_lightness(int i, float black);

}  // namespace candela
