// `perlinfire`: a volumetric, fully procedural fire after NVIDIA's Perlin-fire
// paper. A profile texture swept about y fills a box; each pixel ray-marches
// through it, octaves of noise displacing the profile lookup along y. Made
// for small GPUs: ray steps, octaves and render scale are settings, and an
// automatic mode trades them for frame time (QualityGovernor). Wind from the
// scene's WindField bends the flame and drifts its turbulence.
#pragma once

#include <string>
#include <string_view>

#include "scene/element.h"

namespace candela {

enum class FireNoise { kSimplex3d, kFlow3d, kSimplex4d, kPerlin4d };

// How the march turns what it meets into light: kSheets cuts the profile's
// density at a sharp threshold (tongues, crisp edges, clipped cores, a
// black-body ramp; the default), kProfile sums the profile's colours (the
// paper's way: soft and gaseous).
enum class FireShading { kProfile = 0, kSheets = 1 };

// The PF_* defines of the fire's shaders: noise kind, shading, the
// constants of noise_tables.h and the swell's number of points.
std::string perlinfire_defines(FireNoise kind, FireShading shading);

// The fire's fragment shader text around another `body` (a whole shader
// file; its #version line is dropped): as the element builds it from
// gles_shaders/perlinfire_noise.frag, fire_ramp.frag and perlinfire.frag
// (compose_shader, gl/program.h), with `body` in place of perlinfire.frag.
// The tests build their noise probes with it.
std::string perlinfire_fragment_source(std::string_view body, FireNoise kind,
                                       FireShading shading = FireShading::kSheets);

const ElementKind& perlinfire_kind();

}  // namespace candela
