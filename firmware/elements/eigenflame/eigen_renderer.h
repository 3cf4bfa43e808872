// Draws one eigen-flame with GLES 3.0:
//  1. reconstruction: mean + sum w_i eigen_i at the model's own resolution
//     into an offscreen RGBA8 texture (gray in red, 0..255 -> 0..1);
//  2. glow: a cheap bloom at half size, coloured and blurred separably;
//  3. composite: a camera-facing billboard (a vertex grid that the Learning
//     Flames shape can deform) adds the coloured flame and its glow onto the scene.
// Weights go to the GPU as a vec4 uniform array; nothing is allocated per frame.
#pragma once

#include <array>
#include <cstdint>
#include <span>

#include "gl/math.h"
#include "gl/program.h"
#include "gl/texture.h"

namespace candela {

// A stack of quantised images: value = offset[i] + scale[i] * raw, raw is U8
// or little-endian U16; rows top first. (A view of model::QuantisedImages.)
struct ImageStack {
  bool u16 = false;
  int count = 0, width = 0, height = 0;
  const uint8_t* data = nullptr;
  std::span<const float> scale, offset;
};

// How the stack is laid out on the GPU: four components per RGBA texel
// (packed) or one per layer of a texture array (layered).
enum class StackLayout { kPacked, kLayered };

// Step 1 alone (also what the tests compare with the CPU reconstruction).
class EigenReconstructor {
 public:
  static constexpr int kMaxComponents = 256;

  // Uploads mean and the first min(eigen.count, max_components) eigen-images.
  EigenReconstructor(const ImageStack& mean, const ImageStack& eigen, StackLayout layout,
                     int max_components = kMaxComponents);
  // Renders into texture(); leaves that framebuffer bound and its viewport set.
  void reconstruct(std::span<const float> weights);
  GLuint texture() const { return target_.get(); }
  GLuint framebuffer() const { return fbo_.get(); }
  int width() const { return width_; }
  int height() const { return height_; }
  int components() const { return components_; }

 private:
  int width_, height_, components_, entries_, layers_;
  StackLayout layout_;
  Program program_;
  Texture stack_, target_;
  Framebuffer fbo_;
  VertexArray vao_;
  GLint u_stack_, u_layers_, u_coef_, u_bias_;
  std::array<float, 4 * (kMaxComponents / 4 + 2)> coef_{};
  float mean_scale_, mean_offset_;
  std::span<const float> eigen_scale_, eigen_offset_;
};

struct FlameLookSettings {
  std::array<uint8_t, 256 * 4> ramp{};  // gray -> RGBA colour
  float brightness = 1.0f;
  float glow_radius = 0.12f;  // fraction of the flame image's height
  float glow_strength = 0.6f;
};

// The flame's pose and shape for one frame.
struct FlamePose {
  Vec3 origin;          // bottom centre of the flame image, world
  float height = 0.5f;  // world height of the flame image
  bool deform = false;  // apply `shape` (Learning Flames)
  static constexpr int kShapeRows = 24;
  // Per grid row (flame base to tip): centre offset and full width of the
  // normalised image, both in flame-image heights.
  std::array<float, 2 * (kShapeRows + 1)> shape{};
  float base = 0;              // flame base above the image's bottom edge, heights
  float height_factor = 1.0f;  // flame base-to-tip length, heights
};

class EigenRenderer {
 public:
  EigenRenderer(const ImageStack& mean, const ImageStack& eigen, StackLayout layout,
                int max_components, const FlameLookSettings& look);
  // Offscreen work (reconstruction and glow); call before the scene's own
  // drawing passes. Restores the caller's framebuffer and viewport.
  void prepare(std::span<const float> weights, int screen_w, int screen_h);
  // Adds the flame and its glow onto the bound framebuffer.
  void composite(const Mat4& view, const Mat4& view_projection, const FlamePose& pose);
  const EigenReconstructor& reconstructor() const { return recon_; }

 private:
  EigenReconstructor recon_;
  FlameLookSettings look_;
  Program glow_, flame_;
  Texture ramp_, glow_a_, glow_b_;
  Framebuffer fbo_a_, fbo_b_;
  VertexArray fullscreen_vao_, grid_vao_;
  Buffer grid_vbo_, grid_ibo_;
  GLsizei grid_indices_ = 0;
  int glow_w_ = 0, glow_h_ = 0, pad_ = 0, radius_ = 0;
  float margin_x_ = 0, margin_y_ = 0;  // glow margin, flame uv
  struct {
    GLint source, ramp, colourise, map, step, radius, sigma;
  } ug_{};
  struct {
    GLint vp, origin, right, size, margin, shape, base, height, deform, gray, glow, ramp,
        brightness, glow_strength;
  } uf_{};
};

// The HLS colour ramp (gray as lightness, fixed hue and saturation), as the
// EigenFires paper colours its flames.
std::array<uint8_t, 256 * 4> hls_ramp(float hue_deg, float saturation);
// A transfer function through evenly spaced colour stops (at least two).
std::array<uint8_t, 256 * 4> transfer_ramp(std::span<const Vec3> stops);

}  // namespace candela
