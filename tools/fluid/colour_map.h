// Temperature -> pixels. Gray is the normalised excess temperature
// s = (T - T_amb) / (T_ref - T_amb), clamped to 0..1. Black-body colours the
// same brightness with the chromaticity of a Planck radiator at T (CIE 1931
// matching functions, multi-lobe fit of Wyman, Sloan and Shirley 2013, to
// linear sRGB, then the sRGB transfer curve).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

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

// Visible luminance (CIE Y) of a black body at `kelvin`, relative to one at
// 1500 K: it climbs about 3 decades from 900 K to 1900 K, which is why a
// flame's edge is crisp although its temperature falls off smoothly.
double black_body_luminance(double kelvin);

// A camera looking at the hot gas: pixel = soft_clip(exposure * Y(T) /
// Y(T_ref)), linear up to `knee`, then rolling off toward 1 (so the core
// clips to white as a real sensor's does), then the sRGB curve. Black-body
// mode clips each channel of the Planck colour that way, so cores go
// red -> yellow -> white as real footage does.
// With a fuel grid and soot > 0, the gas glows in proportion to its
// emissivity 1 - exp(-fuel / soot): soot forms where fuel burns, so the
// visible flame ends where the fuel does (a pointed tip), and the hot but
// clear gas above it stays invisible, as over a real candle.
struct Camera {
  double exposure = 1.0;
  double knee = 0.7;  // 0..1: where the soft clip starts
  double soot = 0.0;  // fuel units for emissivity 1 - 1/e; 0 = every hot cell glows
  // Light a real camera spreads around bright flame (lens scatter, the hot
  // gas's own dim envelope): this share of a Gaussian-blurred copy of the
  // light is added before the soft clip (finish_radiance only). It softens
  // the outer edge and joins tongues that nearly touch, as on video.
  double glow = 0.0;
  double glow_radius = 3.0;  // Gaussian sigma, canvas pixels
  // The lit air and smoke around a fire: a wide blur of the clipped picture
  // (so never brighter than `haze` itself, linear) added after the clip. It
  // gives the flames the dim envelope video shows without joining them.
  double haze = 0.0;
  double haze_radius = 10.0;
};
double soft_clip(double x, double knee);
Image render_radiance(const Grid2& temperature, double t_ambient, double t_reference,
                      ColourMode mode, const Camera& camera, int scale,
                      const Grid2* fuel = nullptr);

// Many slices, one picture (after Horvath and Geiger 2009, who render film
// fire from many 2-D simulations placed in depth): where one simulation's
// slice lands on a wider canvas. Canvas pixel (X, Y), Y top-down, shows grid
// point ((X - left) / scale, (canvas_height - 1 - Y - bottom + 0.5) / scale - 0.5),
// mirrored left-right when `mirror` is set; `gain` dims slices farther back.
struct SlicePlacement {
  double left = 0.0;    // canvas x of the grid's left edge, pixels
  double bottom = 0.0;  // canvas rows between the canvas's bottom and the grid's floor
  double scale = 1.0;   // canvas pixels per cell
  double gain = 1.0;
  bool mirror = false;
  // Light fades to nothing over these shares of the grid at its top and at
  // its sides: gas that leaves a slice's grid inside the canvas would else
  // end along the grid's straight edge.
  double fade_top = 0.0, fade_sides = 0.0;
};
// Adds a slice's linear, exposed luminance (exposure * Y(T)/Y(T_ref) times
// the soot emissivity, as render_radiance computes it before the soft clip)
// to `canvas` (canvas_width x canvas_height, rows top-down). Light adds: the
// slices are thin, mostly transparent glowing gas.
// Y(T)/Y(T_ref) in 10 K steps from T_amb up to twice T_ref: made once per
// clip, read for every pixel of every slice.
struct RadianceTable {
  RadianceTable(double t_ambient, double t_reference);
  double at(double kelvin) const;  // linear between steps, clamped to the table
  double lo, step = 10.0;
  std::vector<double> lum;
};
void add_radiance(const Grid2& temperature, const Grid2* fuel, const RadianceTable& table,
                  const Camera& camera, const SlicePlacement& at, int canvas_width,
                  int canvas_height, std::vector<float>& canvas);
// The canvas with the camera's glow, through its soft clip and the sRGB
// curve: gray pixels.
Image finish_radiance(const std::vector<float>& canvas, int width, int height,
                      const Camera& camera);

}  // namespace candela::fluid
