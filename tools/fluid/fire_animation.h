// Animation from simulated fields and one photo (Kogawa, Dobashi, Yamamoto
// 3.3-3.4): texture synthesis runs on key frames only; between them the
// synthesised image is carried along by the simulation's velocity
// (semi-Lagrangian back-trace, bilinear); a new key frame is synthesised m
// frames before each key time and advected alongside the old chain while the
// output cross-dissolves from the old chain into it over those m frames.
//   key frames synthesised at frames 0, K-m, 2K-m, ...; dissolves over
//   (iK-m, iK]; at iK the new chain has fully taken over.
#pragma once

#include <functional>
#include <string>

#include "field_file.h"
#include "texture_synth.h"

namespace candela::fluid {

struct AnimateParams {
  SynthParams synth;
  int key_interval = 8;      // K, frames between key frames
  int dissolve = 3;          // m, overlapping frames (0 <= m < K)
  int scale = 2;             // output pixels per simulation cell
  bool independent = false;  // synthesise every frame on its own (for comparison)
  uint64_t seed = 1;
};

void validate(const AnimateParams& p);

// The target control for a field: normalised temperature, bilinear-scaled by
// `scale`, rows top-down (fields run bottom-up).
std::vector<float> temperature_target(const FieldFrame& f, int scale);

// Back-traces `image` through the field's cell-centred velocity over
// `seconds` (scaled to output pixels). Returns the advected image.
RgbImage advect_image(const RgbImage& image, const FieldFrame& f, int scale, double seconds);

using FieldSource = std::function<FieldFrame(int)>;
using FrameSink = std::function<void(int, const RgbImage&)>;

struct AnimateStats {
  int key_frames = 0;
};

// Makes `frames` frames from fields 0..frames-1 (fps: field frame rate; the
// fields need velocity unless every frame is synthesised independently).
AnimateStats animate_fire(const Exemplar& photo, const AnimateParams& params, int frames,
                          double fps, const FieldSource& fields, const FrameSink& sink);

Image to_image(const RgbImage& rgb);

}  // namespace candela::fluid
