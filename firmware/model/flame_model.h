// A flame model as the runtime sees it: typed, validated views into a loaded
// model file (no copies, no Eigen). Written by `candela-tool build`.
//
// Tensors (E components, F frames, H x W pixels; images row-major, top row first):
//   mean.q [1,H,W] + mean.scale/offset [1]      quantised mean image (gray 0..255)
//   eigen.q [E,H,W] + eigen.scale/offset [E]    quantised eigen-images (U8 or U16)
//   weights F32 [F,E]                           per-frame weights of the training frames
//   variance F32 [E]                            explained variance of each component
//   graph.offsets I32 [F+1], graph.successors I32 [M], graph.cost F32 [M]
//                                               motion graph (CSR): good successors of each frame
// Optional Learning Flames part (info "learning_flames"; D = np + nw + 1 + ne):
//   lf.mean.q [1,h,w], lf.eigen.q [ne,h,w] (+ scale/offset)  shape-normalised appearance
//   lf.params F32 [T,D]   training parameters: path[np], width[nw], height, appearance[ne]
//                         (path: centre x in pixels at heights (i+0.5)/np of the flame, base to
//                         tip; width: 2 x the slice's x std; height: base to tip, pixels)
//   arp.A F32 [K,D,D], arp.d F32 [D], arp.B F32 [D,D]   x_t = sum A_k x_{t-k} + d + B w_t
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "model/model_file.h"

namespace candela::model {

// What the runtime's players can play; FlameModel::from refuses more, so a
// model that loads is a model that plays (elements/eigenflame/).
inline constexpr int kMaxArpOrder = 4;  // ArpProcess: K previous states
inline constexpr int kMaxArpDim = 64;   // ArpProcess: np + nw + 1 + ne
inline constexpr int kMaxSuccessors =
    1024;  // GraphWalker: jumps from one frame (sums stay in Q16.16)
inline constexpr double kMaxClipFps = 1000;  // model frames per second x speed (<= 8) in Q16.16
// EigenFires a flame is drawn with (GraphPlayer, StoryPlayer,
// EigenReconstructor); a model may hold more, and plays its first 512. 512
// covers every frame of a clip of 500 frames (20 s at 25 fps), so a user's own
// footage plays back exactly.
inline constexpr int kMaxPlayedComponents = 512;
// What a display can show at frame rate (issue 34: a 16384x4096 model passed
// --check and then took 1.4 GB and tens of seconds a frame): image sides up
// to 2048 (every OpenGL ES 3 GPU's texture limit), and at most 64 Mi texels
// of played eigen-images (components played x width x height; the built-in
// fire has 6 Mi, a 256x320 model of 512 components 40 Mi).
inline constexpr int kMaxModelSide = 2048;
inline constexpr int64_t kMaxModelTexels = int64_t{64} << 20;

// What is wrong with a Learning Flames part of these sizes for the players:
// `field` under "learning_flames" (empty: the sizes together) and the
// problem, or nothing when they can play it. FlameModel::from refuses a file
// that fails this; `candela-tool build` asks it before learning anything.
struct SizeProblem {
  std::string field, problem;
};
std::optional<SizeProblem> learning_flames_size_problem(int np, int nw, int ne, int order);

// A stack of quantised images: value = offset[i] + scale[i] * q.
struct QuantisedImages {
  DType dtype = DType::kU16;
  int count = 0, width = 0, height = 0;
  const uint8_t* data = nullptr;
  std::span<const float> scale, offset;

  size_t pixels() const { return static_cast<size_t>(width) * height; }
  uint32_t raw(int image, size_t pixel) const {
    const size_t at = static_cast<size_t>(image) * pixels() + pixel;
    if (dtype == DType::kU8) return data[at];
    return static_cast<uint32_t>(data[2 * at]) | (static_cast<uint32_t>(data[2 * at + 1]) << 8);
  }
  float value(int image, size_t pixel) const {
    return offset[image] + scale[image] * static_cast<float>(raw(image, pixel));
  }
};

struct MotionGraph {
  std::span<const int32_t> offsets;     // F + 1
  std::span<const int32_t> successors;  // M
  std::span<const float> cost;          // M: distance from the frame to the successor
  float theta_min = 0;                  // steps below this look like slow motion
  std::span<const int32_t> successors_of(int frame) const {
    return successors.subspan(offsets[frame], offsets[frame + 1] - offsets[frame]);
  }
};

struct ClipLabel {
  int from = 0, to = 0;  // global frame range [from, to)
  std::string label;
};
struct ClipInfo {
  std::string name, source;
  int first = 0, count = 0;  // global frame range of the clip
  double fps = 30;
  std::vector<ClipLabel> labels;
};

struct ColourDefaults {
  float hue = 28;  // degrees
  float saturation = 0.9f;
  float glow_radius = 0.06f;  // fraction of the image height
  // Off unless asked for: footage already holds what the camera saw, and an
  // additive glow fills the dark gaps between tongues (a model of the real
  // campfire played with 0.6 lost half its outline complexity and pieces).
  float glow_strength = 0.0f;
  // Intensity (0..255) treated as black before colouring: hides the small
  // reconstruction noise around the flame.
  float black_level = 4;
};

struct LearningFlamesModel {
  int np = 10, nw = 10, ne = 5;
  int dim = 26;                    // np + nw + 1 + ne
  int order = 2;                   // K
  int width = 0, height = 0;       // normalised image size
  float base_y = 0;                // flame base row in the model frame (pixels)
  float span = 2.5f;               // the normalised image covers +-span widths around the path
  QuantisedImages mean, eigen;     // appearance of the normalised flame
  std::span<const float> params;   // T x dim
  int frames = 0;                  // T
  std::span<const float> A, d, B;  // K*dim*dim, dim, dim*dim
};

class FlameModel {
 public:
  // Opens, reads and validates (ModelError on any problem).
  static FlameModel load(const std::string& path);
  static FlameModel from(ModelFile file);

  const ModelFile& file() const { return file_; }
  int width() const { return mean.width; }
  int height() const { return mean.height; }
  int components() const { return eigen.count; }
  int frames() const { return frames_; }
  std::span<const float> weights_of(int frame) const {
    return weights.subspan(static_cast<size_t>(frame) * components(), components());
  }
  int clip_of(int frame) const;
  // Gray image (0..255, not clamped) from weights (uses the first w.size() components).
  void reconstruct(std::span<const float> w, std::span<float> out) const;
  // For a model built into the binary, once its images are on the GPU: gives
  // their pages back (ModelFile::give_back_pages; reconstruct() still works,
  // paging them in again). Returns the bytes given back.
  size_t give_back_image_pages() const;

  QuantisedImages mean, eigen;
  std::span<const float> weights, variance;
  double total_variance = 0;  // of the training frames (per frame, summed over pixels)
  MotionGraph graph;
  std::vector<ClipInfo> clips;
  ColourDefaults colour;
  bool has_learning_flames = false;
  LearningFlamesModel flames;

 private:
  ModelFile file_;
  int frames_ = 0;
};

}  // namespace candela::model
