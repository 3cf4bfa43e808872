// Texture synthesis with user control after Ashikhmin ("Synthesizing Natural
// Textures", 2001), as Kogawa, Dobashi and Yamamoto use it to put a fire
// photograph's detail onto a simulated temperature field.
//
// The output starts as white noise (random photo pixels) and is visited in
// raster order. Each output pixel p is given the photo pixel whose
// neighbourhood is closest by sum of squared differences over two parts:
//   upper L (rows above p, and the pixels left of p): output colour vs photo
//     colour;
//   lower L (p, the pixels right of p, and the rows below): target control
//     (the simulated temperature) vs the photo's control channel (its alpha,
//     or its luminance for a photo of fire on a dark background).
// Candidates (nearest-neighbour search): Ashikhmin's coherent candidates, i.e.
// for every already-synthesised neighbour q, the photo pixel that continues
// q's source by the offset p - q, plus a few uniformly random photo pixels so
// the search can leave a patch (random_candidates, default 4).
#pragma once

#include <cstdint>
#include <vector>

#include "core/image.h"
#include "core/random.h"

namespace candela::fluid {

// Float RGB image in 0..1, rows top-down.
struct RgbImage {
  int width = 0;
  int height = 0;
  std::vector<float> px;  // 3 per pixel
  float* at(int x, int y) { return &px[3 * (static_cast<size_t>(y) * width + x)]; }
  const float* at(int x, int y) const { return &px[3 * (static_cast<size_t>(y) * width + x)]; }
};

enum class ControlChannel { kAuto, kAlpha, kLuminance };

// The photo as the synthesiser sees it: colour premultiplied by alpha (so a
// transparent background reads as black) and a control channel scaled so its
// maximum is 1.
struct Exemplar {
  int width = 0;
  int height = 0;
  std::vector<float> rgb;      // 3 per pixel
  std::vector<float> control;  // 1 per pixel
};

// kAuto: alpha when the photo has one, else luminance. Throws
// std::invalid_argument when the photo is too small or its control is all 0.
Exemplar make_exemplar(const Image& photo, ControlChannel channel, int min_size);

struct SynthParams {
  int neighbourhood = 5;        // odd, >= 3: the L-shapes span n x n
  int random_candidates = 4;    // extra random photo pixels per output pixel
  double control_weight = 3.0;  // weight of the lower-L (temperature) SSD
  int passes = 1;               // the paper: one raster pass
};

// Throws std::invalid_argument naming the bad parameter.
void validate(const SynthParams& p);

class TextureSynthesizer {
 public:
  TextureSynthesizer(const Exemplar& photo, const SynthParams& params);

  // target: width*height control values (0..1), rows top-down.
  RgbImage synthesize(const std::vector<float>& target, int width, int height, Pcg32& rng);
  // Photo coordinates (y * photo width + x) each output pixel came from, for
  // the last synthesize() call.
  const std::vector<int32_t>& sources() const { return source_; }

 private:
  float cost(int px, int py, int cand, const std::vector<float>& target, int w, int h,
             float best) const;

  const Exemplar& photo_;
  SynthParams params_;
  int r_ = 2;
  // The photo padded by r on each side (edge copies) so neighbourhood reads
  // need no clamping.
  int pw_ = 0, ph_ = 0;
  std::vector<float> prgb_, pctl_;
  std::vector<int32_t> source_;
  std::vector<float> out_;
};

}  // namespace candela::fluid
