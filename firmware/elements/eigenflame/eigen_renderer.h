// Draws one eigen-flame with GLES 3.0:
//  1. reconstruction: mean + sum w_i eigen_i at the model's own resolution
//     into an offscreen RGBA8 texture (gray in red, 0..255 -> 0..1);
//  2. glow: a cheap bloom at half size, coloured and blurred separably;
//  3. sprite: colour (ramp) + brightness + glow at the model's resolution;
//  4. composite: a camera-facing billboard (a vertex grid that the Learning
//     Flames shape can deform) adds the sprite onto the scene.
// Weights go to the GPU as a vec4 uniform array; nothing is allocated per frame.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "gl/math.h"
#include "gl/program.h"
#include "gl/render_target.h"
#include "gl/texture.h"
#include "model/colour_ramp.h"
#include "model/flame_model.h"
#include "scene/element.h"

namespace candela {

// A stack of quantised images: value = offset[i] + scale[i] * raw, raw is U8
// or little-endian U16; rows top first. (A view of model::QuantisedImages.)
struct ImageStack {
  bool u16 = false;
  int count = 0, width = 0, height = 0;
  const uint8_t* data = nullptr;
  std::span<const float> scale, offset;
};

namespace model {
struct QuantisedImages;
}
// The view of a model's images (the one adapter from model/ to the renderer).
ImageStack image_stack_of(const model::QuantisedImages& q);

// How the stack is laid out on the GPU: four components per RGBA texel
// (packed) or one per layer of a texture array (layered).
enum class StackLayout { kPacked, kLayered };

// Step 1 alone (also what the tests compare with the CPU reconstruction).
class EigenReconstructor {
 public:
  static constexpr int kMaxComponents = model::kMaxPlayedComponents;

  // Uploads mean and the first min(eigen.count, max_components) eigen-images.
  EigenReconstructor(const ImageStack& mean, const ImageStack& eigen, StackLayout layout,
                     int max_components = kMaxComponents);
  // Renders into texture(); leaves that framebuffer bound and its viewport set.
  void reconstruct(std::span<const float> weights);
  // Renders into the bound framebuffer at (x, y), model-sized.
  void draw_at(std::span<const float> weights, int x, int y);

  // The frame cache. A graph walk shows the model's own frames, each again
  // and again over the hours: each frame's reconstruction is kept (an R8
  // texture-array layer) the first time it is shown, and later draws of it
  // read one texel instead of summing every component. `frame_weights`
  // holds `frames` rows of `stride` weights and must outlive the
  // reconstructor. Returns false (no cache; draws stay on the full sum)
  // where the frames would take over 64 MiB or more layers than the GPU has.
  bool enable_cache(std::span<const float> frame_weights, int frames, int stride);
  // Makes sure frame `frame`'s reconstruction is cached (a full sum into its
  // layer the first time; binds the cache's framebuffer then). Call outside
  // the draw into the target: it changes the bound framebuffer.
  void cache_frame(int frame);
  // As draw_at, for weights near those of model frame `frame` (cached by
  // cache_frame): the cached frame plus the sum over the components in which
  // the weights differ from it (none for a held frame: exactly the full
  // sum's pixels; the first kBlendComponents near a walk's jump). Without a
  // cache or a frame (< 0), the full sum.
  void draw_near_frame_at(std::span<const float> weights, int frame, int x, int y);
  bool caches() const { return cache_frames_ > 0; }
  GLuint texture() const { return target_.texture(); }
  GLuint framebuffer() const { return target_.framebuffer(); }
  int width() const { return width_; }
  int height() const { return height_; }
  int components() const { return components_; }

 private:
  // eigenflame_reconstruct.frag: the full sum, the sum into the cache
  // (TO_CACHE) and a cached frame plus a difference (FROM_CACHE).
  struct ReconstructProgram {
    ReconstructProgram() = default;
    explicit ReconstructProgram(const std::string& defines);
    Program program;
    GLint stack = -1, layers = -1, coef = -1, bias = -1, origin = -1, cache = -1, frame = -1;
  };
  // `base`: the cached frame's weights (sum only the difference; `frame` its
  // layer), or null for the full sum.
  void draw_with(const ReconstructProgram& p, std::span<const float> weights, const float* base,
                 int frame, int x, int y);
  // The shader's defines for this stack (its uniform array size, its layout).
  std::string program_defines() const;

  // The stack's entries: the mean (two: its high and low bytes, where a
  // 16-bit mean goes with 8-bit eigen-images), then each eigen-image.
  int width_, height_, components_, mean_entries_, entries_, layers_;
  bool layered_;
  bool pixel_major_ = false;  // the stack's texel (entry layer, x) in layer y (the constructor)
  ReconstructProgram full_, fill_, near_;
  Texture stack_;
  RenderTarget target_;
  VertexArray vao_;
  std::array<float, 4 * (kMaxComponents / 4 + 2)> coef_{};
  float mean_scale_, mean_offset_;
  std::span<const float> eigen_scale_, eigen_offset_;
  // The frame cache (enable_cache).
  int cache_frames_ = 0, cache_stride_ = 0;
  // A copy: the weights may be a flame's own (its scene's weight edits), and
  // the reconstructor outlives that flame when others of its model share it.
  std::vector<float> cache_weights_;
  std::vector<bool> cached_;
  Texture cache_;
  Framebuffer cache_fbo_;
};

struct FlameLookSettings {
  std::array<uint8_t, 256 * 4> ramp{};  // gray -> RGBA colour
  float brightness = 1.0f;
  float glow_radius = 0.12f;  // fraction of the flame image's height
  float glow_strength = 0.6f;
  float edge_fade = 0.05f;  // sides and top faded over this share of the image
  // Heights (0 bottom .. 1 top of the image) between which its foot fades in:
  // nothing below the first, all of it above the second (0, 0: no fade).
  float foot_fade[2] = {0, 0};
};

// The flame's pose and shape for one frame.
struct FlamePose {
  Vec3 origin;          // bottom centre of the flame image, world
  float height = 0.5f;  // world height of the flame image
  float widen = 1.0f;   // rigid: width scale of the image
  bool deform = false;  // apply `shape` (Learning Flames)
  static constexpr int kShapeRows = 24;
  // Per grid row (flame base to tip): centre offset and full width of the
  // normalised image, both in flame-image heights.
  std::array<float, 2 * (kShapeRows + 1)> shape{};
  float base = 0;              // flame base above the image's bottom edge, heights
  float height_factor = 1.0f;  // flame base-to-tip length, heights
  float light = 1.0f;          // the flame's light this frame (its flicker), times the sprite
};

class EigenBatch;

// One flame's share of the batch's offscreen work: what it reconstructs, how
// its glow and colour are made, and (set by the batch's layout) where it
// lies in the atlases. Its EigenRenderer fills it in and owns it.
struct EigenSpriteJob {
  EigenReconstructor* recon = nullptr;
  std::span<const float> weights;  // read at every prepare
  int32_t frame = -1;              // the model frame the weights are near (-1: none)
  GLuint ramp = 0;                 // 256x1 colour ramp texture
  float brightness = 1, glow_strength = 0, edge_fade = 0;
  float foot_fade[2] = {0, 0};
  int glow_w = 0, glow_h = 0;          // half size, padded by the glow's radius
  static constexpr int kMaxTaps = 17;  // eigenflame_glow.frag's MAX_TAPS
  int taps = 1;                        // centre + bilinear pairs
  std::array<float, kMaxTaps> tap_offset{}, tap_weight{};
  Vec3 glow_tint;
  float margin_x = 0, margin_y = 0;  // glow margin, flame uv
  int sprite_w = 0, sprite_h = 0;
  // Places in the atlases (EigenBatch's layout).
  int gray_x = 0, gray_y = 0, glow_x = 0, glow_y = 0, sprite_x = 0, sprite_y = 0;
  int cells_y = 0;  // its first row in the cells atlas (which billboard cells are black)
  // The weights its sprite in the atlas shows (EigenBatch::render redraws
  // only flames whose weights changed: a held model frame costs nothing).
  std::array<float, EigenReconstructor::kMaxComponents> drawn{};
  bool drawn_valid = false, redraw = true;
};

// One flame's GPU side. Its offscreen work (reconstruction, glow, the
// finished sprite) is done by an EigenBatch together with every other
// eigen-flame's of the scene, in shared atlas textures: four render-target
// switches per frame however many flames (each makes llvmpipe and tiled GPUs
// flush). The billboard then costs one bilinear fetch per screen pixel.
class EigenRenderer {
 public:
  // `weights` must stay valid (the element's own array); read at every
  // prepare. `batch`: the batch this flame's offscreen work joins (in a
  // scene, the scene's: SceneResources::get<EigenBatch>()), which must
  // outlive the renderer; null: a batch of its own (one flame alone, as a
  // tool draws it).
  EigenRenderer(const ImageStack& mean, const ImageStack& eigen, StackLayout layout,
                int max_components, const FlameLookSettings& look, std::span<const float> weights,
                EigenBatch* batch = nullptr);
  ~EigenRenderer();
  EigenRenderer(const EigenRenderer&) = delete;
  EigenRenderer& operator=(const EigenRenderer&) = delete;

  // The offscreen work of this flame's batch (every member's): call once a
  // frame before drawing into the screen. Restores the caller's framebuffer
  // and viewport. In a scene the scene does this, once for the shared batch.
  void prepare();
  // Adds the flame and its glow onto the bound framebuffer.
  void composite(const Mat4& view, const Mat4& view_projection, const FlamePose& pose);
  // Grows `box` (world) to hold what composite() draws for `pose`: the
  // billboard eigenflame.vert makes, its glow's margin included.
  void add_bounds(const Mat4& view, const FlamePose& pose, Box3& box) const;
  const EigenReconstructor& reconstructor() const { return *recon_; }
  // The model's frames (rows of `stride` weights), for the frame cache
  // (EigenReconstructor::enable_cache); then set_frame names the frame the
  // weights are near, at each update. Does nothing unless wants_frame_cache().
  void cache_frames(std::span<const float> frame_weights, int frames, int stride);
  // Whether cache_frames would cache: a model with a long sum whose frames
  // no flame sharing its reconstructor has cached yet (ask before preparing
  // the frames' weights).
  bool wants_frame_cache() const;
  void set_frame(int32_t frame) { job_.frame = frame; }

 private:
  std::shared_ptr<EigenReconstructor> recon_;  // shared with the batch's other flames of its model
  Texture ramp_;
  EigenSpriteJob job_;
  std::unique_ptr<EigenBatch> own_batch_;  // when made without a shared one
  EigenBatch* batch_;
};

// The shared offscreen stage of a scene's eigen-flames (a SceneResource: the
// scene prepares it once per frame, after every element's prepare).
class EigenBatch final : public SceneResource {
 public:
  EigenBatch();
  void add(EigenSpriteJob* job);
  void remove(EigenSpriteJob* job);
  // The reconstructor of these images: one per model (and layout and
  // component count) however many of the scene's flames play it, so its
  // stack, and its frame cache, are uploaded and filled once. The images
  // must outlive every renderer holding it (the flames hold their model).
  std::shared_ptr<EigenReconstructor> reconstructor(const ImageStack& mean, const ImageStack& eigen,
                                                    StackLayout layout, int max_components);
  // Every member's reconstruction, glow and sprite into the atlases, for
  // the members whose weights changed since they were last drawn. Restores
  // the caller's framebuffer and viewport.
  void render();
  void prepare(const FrameContext&) override { render(); }

  GLuint sprite_atlas() const { return sprite_.texture(); }
  const Program& flame_program() const { return flame_; }
  // Per flame, which cells of its billboard grid add any light (1) and which
  // are black (0): the billboard draws only the first (eigenflame_cells.frag).
  GLuint cells_atlas() const { return cells_.texture(); }
  GLuint grid_vao() const { return grid_vao_.get(); }
  GLsizei grid_vertices() const { return grid_vertices_; }
  struct FlameUniforms {
    GLint vp, origin, right, size, margin, shape, base, height, deform, sprite, sprite_rect, light,
        cells, cells_row;
  };
  const FlameUniforms& flame_uniforms() const { return uf_; }

 private:
  void layout();
  std::vector<EigenSpriteJob*> members_;
  struct SharedReconstructor {
    const uint8_t *mean, *eigen;
    StackLayout layout;
    int max_components;
    std::weak_ptr<EigenReconstructor> reconstructor;
  };
  std::vector<SharedReconstructor> reconstructors_;
  bool laid_out_ = false;
  RenderTarget gray_, glow_a_, glow_b_, sprite_, cells_;
  Program glow_, sprite_program_, flame_, cells_program_;
  VertexArray fullscreen_vao_, grid_vao_;
  Buffer grid_vbo_;
  GLsizei grid_vertices_ = 0;
  struct {
    GLint sprite, sprite_rect, origin, cells;
  } uc_{};
  struct {
    GLint source, map, step, taps, offset, weight, clamp_rect, mask;
  } ug_{};
  struct {
    GLint gray, glow, ramp, gray_rect, glow_rect, margin, brightness, glow_strength, glow_tint,
        edge_fade, foot_fade;
  } us_{};
  FlameUniforms uf_{};
};

// A transfer function through colour stops (at least two), linear between
// them: evenly spaced, or at `positions` (one per stop, 0..1 of the lightness
// above `black`, non-decreasing; below the first the first colour, above the
// last the last).
std::array<uint8_t, 256 * 4> transfer_ramp(std::span<const Vec3> stops, float black = 0,
                                           std::span<const float> positions = {});

}  // namespace candela
