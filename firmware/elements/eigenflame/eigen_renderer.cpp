#include "elements/eigenflame/eigen_renderer.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/log.h"
#include "model/flame_model.h"

namespace candela {

ImageStack image_stack_of(const model::QuantisedImages& q) {
  return {q.dtype == model::DType::kU16, q.count, q.width, q.height, q.data, q.scale, q.offset};
}

namespace {

constexpr int kGridColumns = 8;

uint32_t raw_at(const ImageStack& s, int image, size_t pixel) {
  const size_t at = static_cast<size_t>(image) * s.width * s.height + pixel;
  if (!s.u16) return s.data[at];
  return static_cast<uint32_t>(s.data[2 * at]) | (static_cast<uint32_t>(s.data[2 * at + 1]) << 8);
}

}  // namespace

EigenReconstructor::EigenReconstructor(const ImageStack& mean, const ImageStack& eigen,
                                       StackLayout layout, int max_components)
    : width_(mean.width),
      height_(mean.height),
      components_(std::clamp(std::min(eigen.count, max_components), 0, kMaxComponents)),
      // A 16-bit mean with 8-bit eigen-images: the mean as two 8-bit
      // entries (high byte, low byte) rather than the whole stack widened to
      // 16 bits, which doubled the fire model's texture (6 -> 12 MB).
      mean_entries_(mean.u16 && !eigen.u16 ? 2 : 1),
      entries_(components_ + mean_entries_),
      layers_(layout == StackLayout::kPacked ? (entries_ + 3) / 4 : entries_),
      layered_(layout == StackLayout::kLayered),
      mean_scale_(mean.scale[0]),
      mean_offset_(mean.offset[0]),
      eigen_scale_(eigen.scale),
      eigen_offset_(eigen.offset) {
  if (mean.width != eigen.width || mean.height != eigen.height || width_ < 1 || height_ < 1)
    throw RuntimeError("eigenflame: mean and eigen-images differ in size");
  // 16-bit entries only for 16-bit eigen-images (a 16-bit mean alone is split).
  const bool wide = eigen.u16;
  const int channels = layout == StackLayout::kPacked ? 4 : 1;
  const size_t px = static_cast<size_t>(width_) * height_;
  // Pixel-major where the GPU's limits allow: the texture's layer is the
  // image row, its texel (layer l, pixel x), so one pixel's entries lie side
  // by side in memory. Layer-major (layer l, texel (x, y)) every entry of a
  // pixel is a whole image away from the last: on a software rasteriser each
  // fetch then misses the caches and the TLB, and a full sum of the fire
  // model took ~45 ms on a busy 2-core machine. Same values, same sum.
  GLint max_size = 0, max_layers = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
  glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &max_layers);
  pixel_major_ = layers_ <= max_size && width_ <= max_size && height_ <= max_layers;
  // Raw quantised values, the mean's entries first, widened to 16 bits if
  // the eigen-images are, uploaded one slice at a time (an image row pixel-major, a layer
  // otherwise): the whole stack widened at once was a second copy of the
  // model's images in memory at load (13 MB for the fire model).
  const int tex_w = pixel_major_ ? layers_ : width_, tex_h = pixel_major_ ? width_ : height_;
  const int tex_d = pixel_major_ ? height_ : layers_;
  const GLenum internal =
      channels == 4 ? (wide ? GL_RGBA16UI : GL_RGBA8UI) : (wide ? GL_R16UI : GL_R8UI);
  const GLenum format = channels == 4 ? GL_RGBA_INTEGER : GL_RED_INTEGER;
  stack_ = make_texture();
  glBindTexture(GL_TEXTURE_2D_ARRAY, stack_.get());
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexStorage3D(GL_TEXTURE_2D_ARRAY, 1, internal, tex_w, tex_h, tex_d);
  const size_t slice = static_cast<size_t>(tex_w) * static_cast<size_t>(tex_h) * channels;
  std::vector<uint16_t> wide_data(wide ? slice : 0);
  std::vector<uint8_t> narrow_data(wide ? 0 : slice);
  const auto put = [&](size_t at, uint32_t v) {
    if (wide)
      wide_data[at] = static_cast<uint16_t>(v);
    else
      narrow_data[at] = static_cast<uint8_t>(v);
  };
  const auto entry_at = [&](int e, size_t p) -> uint32_t {
    if (e >= mean_entries_) return raw_at(eigen, e - mean_entries_, p);
    const uint32_t m = raw_at(mean, 0, p);
    return mean_entries_ == 1 ? m : e == 0 ? m >> 8 : m & 0xFFu;
  };
  for (int z = 0; z < tex_d; ++z) {
    std::fill(wide_data.begin(), wide_data.end(), uint16_t{0});  // the last layer's unused channels
    std::fill(narrow_data.begin(), narrow_data.end(), uint8_t{0});
    if (pixel_major_) {  // slice z: image row z; texel (entry layer, x)
      for (int e = 0; e < entries_; ++e) {
        const int layer = channels == 4 ? e / 4 : e, ch = channels == 4 ? e % 4 : 0;
        for (int x = 0; x < width_; ++x)
          put((static_cast<size_t>(x) * static_cast<size_t>(layers_) + static_cast<size_t>(layer)) *
                      channels +
                  static_cast<size_t>(ch),
              entry_at(e, static_cast<size_t>(z) * static_cast<size_t>(width_) + x));
      }
    } else {  // slice z: layer z, its entries' whole images
      for (int ch = 0; ch < channels; ++ch) {
        const int e = z * channels + ch;
        if (e >= entries_) break;
        for (size_t p = 0; p < px; ++p) put(p * channels + static_cast<size_t>(ch), entry_at(e, p));
      }
    }
    glTexSubImage3D(GL_TEXTURE_2D_ARRAY, 0, 0, 0, z, tex_w, tex_h, 1, format,
                    wide ? GL_UNSIGNED_SHORT : GL_UNSIGNED_BYTE,
                    wide ? static_cast<const void*>(wide_data.data()) : narrow_data.data());
  }
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_NEAREST);

  full_ = ReconstructProgram(program_defines());
  target_ = RenderTarget::checked(width_, height_, "eigenflame: reconstruction");
  vao_ = make_vertex_array();
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

void EigenReconstructor::reconstruct(std::span<const float> weights) {
  target_.bind();
  draw_at(weights, 0, 0);
}

EigenReconstructor::ReconstructProgram::ReconstructProgram(const std::string& defines)
    : program(Program::from_library("fullscreen.vert", "eigenflame_reconstruct.frag", defines)),
      stack(program.uniform("u_stack")),
      layers(program.uniform("u_layers")),
      coef(program.uniform("u_coef")),
      bias(program.uniform("u_bias")),
      origin(program.uniform("u_origin")),
      cache(program.uniform("u_cache")),
      frame(program.uniform("u_frame")) {}

std::string EigenReconstructor::program_defines() const {
  return "#define MAX_VEC4 " + std::to_string(coef_.size() / 4) + "\n" +
         (layered_ ? "#define LAYERED\n" : "") + (pixel_major_ ? "#define PIXEL_MAJOR\n" : "");
}

void EigenReconstructor::draw_at(std::span<const float> weights, int x, int y) {
  draw_with(full_, weights, nullptr, -1, x, y);
}

void EigenReconstructor::draw_with(const ReconstructProgram& p, std::span<const float> weights,
                                   const float* base, int frame, int x, int y) {
  // Fold weights and dequantisation: sum_k w_k (offset_k + scale_k q_k)
  //   = sum_k (w_k scale_k) q_k + sum_k w_k offset_k.
  // From a cached frame (`base`, its weights), only the difference is summed:
  // the mean and every component past the last that differs add nothing.
  const int n = std::min(components_, static_cast<int>(weights.size()));
  const float mean_coef = base ? 0.0f : mean_scale_;
  coef_[0] = mean_entries_ == 2 ? mean_coef * 256.0f : mean_coef;  // the high byte
  if (mean_entries_ == 2) coef_[1] = mean_coef;
  float bias = base ? 0.0f : mean_offset_;
  int last = base ? 0 : components_;  // eigen-images summed
  for (int k = 0; k < components_; ++k) {
    const float w = (k < n ? weights[static_cast<size_t>(k)] : 0.0f) - (base ? base[k] : 0.0f);
    coef_[static_cast<size_t>(k + mean_entries_)] = w * eigen_scale_[static_cast<size_t>(k)];
    bias += w * eigen_offset_[static_cast<size_t>(k)];
    if (base && w != 0.0f) last = k + 1;
  }
  const int needed = last + mean_entries_;
  const int layers = last == components_ ? layers_ : layered_ ? needed : (needed + 3) / 4;
  glViewport(x, y, width_, height_);
  glDisable(GL_BLEND);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_SCISSOR_TEST);
  p.program.use();
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D_ARRAY, stack_.get());
  glUniform1i(p.stack, 0);
  if (frame >= 0) {
    glActiveTexture(GL_TEXTURE1);
    glBindTexture(GL_TEXTURE_2D_ARRAY, cache_.get());
    glUniform1i(p.cache, 1);
    glUniform1i(p.frame, frame);
    glActiveTexture(GL_TEXTURE0);
  }
  glUniform1i(p.layers, layers);
  glUniform4fv(p.coef, (entries_ + 3) / 4, coef_.data());
  glUniform1f(p.bias, bias);
  glUniform2i(p.origin, x, y);
  glBindVertexArray(vao_.get());
  glDrawArrays(GL_TRIANGLES, 0, 3);
}

bool EigenReconstructor::enable_cache(std::span<const float> frame_weights, int frames,
                                      int stride) {
  // 2 bytes a pixel a frame: R16UI, the unclamped sum in 1/64 gray levels,
  // so that a difference added later starts from the true sum (an 8-bit,
  // clamped copy would lose what lies below black).
  constexpr size_t kMaxCacheBytes = size_t{64} << 20;
  GLint max_layers = 0;
  glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &max_layers);
  const size_t bytes = size_t{2} * width_ * height_ * static_cast<size_t>(frames);
  if (frames < 1 || stride < components_ ||
      frame_weights.size() < static_cast<size_t>(frames) * static_cast<size_t>(stride) ||
      frames > max_layers || bytes > kMaxCacheBytes)
    return false;
  cache_ = make_texture();
  glBindTexture(GL_TEXTURE_2D_ARRAY, cache_.get());
  glTexStorage3D(GL_TEXTURE_2D_ARRAY, 1, GL_R16UI, width_, height_, frames);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  cache_fbo_ = make_framebuffer();
  fill_ = ReconstructProgram(program_defines() + "#define TO_CACHE\n");
  near_ = ReconstructProgram(program_defines() + "#define FROM_CACHE\n");
  cached_.assign(static_cast<size_t>(frames), false);
  cache_weights_.assign(frame_weights.begin(), frame_weights.end());
  cache_stride_ = stride;
  cache_frames_ = frames;
  return true;
}

void EigenReconstructor::cache_frame(int frame) {
  if (frame < 0 || frame >= cache_frames_ || cached_[static_cast<size_t>(frame)]) return;
  glBindFramebuffer(GL_FRAMEBUFFER, cache_fbo_.get());
  glFramebufferTextureLayer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, cache_.get(), 0, frame);
  const std::span<const float> w =
      std::span<const float>(cache_weights_)
          .subspan(static_cast<size_t>(frame) * static_cast<size_t>(cache_stride_),
                   static_cast<size_t>(components_));
  draw_with(fill_, w, nullptr, -1, 0, 0);
  cached_[static_cast<size_t>(frame)] = true;
}

void EigenReconstructor::draw_near_frame_at(std::span<const float> weights, int frame, int x,
                                            int y) {
  if (frame < 0 || frame >= cache_frames_ || !cached_[static_cast<size_t>(frame)]) {
    draw_at(weights, x, y);
    return;
  }
  draw_with(near_, weights,
            cache_weights_.data() + static_cast<size_t>(frame) * static_cast<size_t>(cache_stride_),
            frame, x, y);
}

// ---------------------------------------------------------------------------

EigenRenderer::EigenRenderer(const ImageStack& mean, const ImageStack& eigen, StackLayout layout,
                             int max_components, const FlameLookSettings& look,
                             std::span<const float> weights, EigenBatch* batch) {
  if (!batch) {
    own_batch_ = std::make_unique<EigenBatch>();
    batch = own_batch_.get();
  }
  recon_ = batch->reconstructor(mean, eigen, layout, max_components);
  const int h = recon_->height(), w = recon_->width();
  ramp_ = upload_rgba8(256, 1, look.ramp.data(), true);
  glBindTexture(GL_TEXTURE_2D, ramp_.get());
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  EigenSpriteJob& j = job_;
  j.recon = recon_.get();
  j.weights = weights;
  j.ramp = ramp_.get();
  j.brightness = look.brightness;
  j.glow_strength = look.glow_strength;
  j.edge_fade = look.edge_fade;
  j.foot_fade[0] = look.foot_fade[0];
  j.foot_fade[1] = look.foot_fade[1];
  // Glow at half size, padded by its radius on every side.
  const int half_w = (w + 1) / 2, half_h = (h + 1) / 2;
  const int radius = std::clamp(static_cast<int>(std::ceil(look.glow_radius * half_h)), 1, 32);
  j.glow_w = half_w + 2 * radius;
  j.glow_h = half_h + 2 * radius;
  // Gaussian taps (sigma = radius / 2), paired for bilinear fetches: one
  // fetch between texels i and i + 1 reads both with the right weights.
  {
    const double sigma = std::max(0.5, radius * 0.5);
    auto g = [&](int i) { return std::exp(-0.5 * i * i / (sigma * sigma)); };
    double total = g(0);
    for (int i = 1; i <= radius; ++i) total += 2 * g(i);
    j.tap_offset[0] = 0;
    j.tap_weight[0] = static_cast<float>(g(0) / total);
    j.taps = 1;
    for (int i = 1; i <= radius && j.taps < EigenSpriteJob::kMaxTaps; i += 2) {
      const double a = g(i), b = i + 1 <= radius ? g(i + 1) : 0.0;
      j.tap_offset[static_cast<size_t>(j.taps)] =
          static_cast<float>((i * a + (i + 1) * b) / (a + b));
      j.tap_weight[static_cast<size_t>(j.taps)] = static_cast<float>((a + b) / total);
      ++j.taps;
    }
  }
  // The glow's colour: twice the ramp's colour at mid gray, so a dim glow
  // matches the coloured flame. (The HLS ramp now keeps luma, so its mid gray
  // is a little lighter and less saturated than the pure hue was.)
  j.glow_tint = {look.ramp[128 * 4] * (2.0f / 255), look.ramp[128 * 4 + 1] * (2.0f / 255),
                 look.ramp[128 * 4 + 2] * (2.0f / 255)};
  j.margin_x = look.glow_strength > 0 ? static_cast<float>(radius) / half_w : 0.0f;
  j.margin_y = look.glow_strength > 0 ? static_cast<float>(radius) / half_h : 0.0f;
  j.sprite_w = w + 2 * static_cast<int>(std::lround(j.margin_x * w));
  j.sprite_h = h + 2 * static_cast<int>(std::lround(j.margin_y * h));
  batch_ = batch;
  batch_->add(&job_);
}

EigenRenderer::~EigenRenderer() { batch_->remove(&job_); }

bool EigenRenderer::wants_frame_cache() const {
  // Worth it for a long sum only: the candle model's 80 components cost 21
  // fetches a pixel, its 3600 frames 100 MB; the fire's 299, 75 fetches.
  constexpr int kCacheFromComponents = 128;
  return recon_->components() >= kCacheFromComponents && !recon_->caches();
}

void EigenRenderer::cache_frames(std::span<const float> frame_weights, int frames, int stride) {
  if (!wants_frame_cache()) return;
  const FramebufferRestore caller;
  if (!recon_->enable_cache(frame_weights, frames, stride))
    LOG_INFO("eigenflame: %d frames of %dx%d not cached (over 64 MiB or the GPU's layers)", frames,
             recon_->width(), recon_->height());
}

void EigenRenderer::prepare() { batch_->render(); }

namespace {
// The billboard's +u direction: the camera's right, level (eigenflame.vert
// turns the flame about the vertical only).
Vec3 billboard_right(const Mat4& view) {
  const Vec3 right{view.at(0, 0), 0.0f, view.at(0, 2)};
  return length(right) > 1e-6f ? normalize(right) : Vec3{1, 0, 0};
}
}  // namespace

void EigenRenderer::add_bounds(const Mat4& view, const FlamePose& pose, Box3& box) const {
  // eigenflame.vert's positions, in flame-image heights: x across (along
  // `right`), y up. Linear in uv within a shape row, and the rows' centres
  // and widths interpolate linearly between the rows, so the extremes lie
  // at the rows' ends.
  const float mx = job_.margin_x, my = job_.margin_y;
  const float aspect = static_cast<float>(recon_->width()) / recon_->height();
  float x0 = 0, x1 = 0, y0 = 0, y1 = 0;
  if (pose.deform) {
    x0 = INFINITY;
    x1 = -INFINITY;
    for (int i = 0; i <= FlamePose::kShapeRows; ++i) {
      const float c = pose.shape[2 * i], w = std::abs(pose.shape[2 * i + 1]);
      x0 = std::min(x0, c - (0.5f + mx) * w);
      x1 = std::max(x1, c + (0.5f + mx) * w);
    }
    const float a = pose.base - my * pose.height_factor;
    const float b = pose.base + (1.0f + my) * pose.height_factor;
    y0 = std::min(a, b);
    y1 = std::max(a, b);
  } else {
    x1 = (0.5f + mx) * aspect * pose.widen;
    x0 = -x1;
    y0 = -my;
    y1 = 1.0f + my;
  }
  const Vec3 right = billboard_right(view);
  for (float x : {x0, x1})
    for (float y : {y0, y1}) box.add(pose.origin + (right * x + Vec3{0, y, 0}) * pose.height);
}

void EigenRenderer::composite(const Mat4& view, const Mat4& view_projection,
                              const FlamePose& pose) {
  const Vec3 right = billboard_right(view);
  const float aspect = static_cast<float>(recon_->width()) / recon_->height();
  const EigenBatch::FlameUniforms& u = batch_->flame_uniforms();
  batch_->flame_program().use();
  glUniformMatrix4fv(u.vp, 1, GL_FALSE, view_projection.m);
  glUniform3f(u.origin, pose.origin.x, pose.origin.y, pose.origin.z);
  glUniform3f(u.right, right.x, right.y, right.z);
  glUniform2f(u.size, pose.height * aspect * pose.widen, pose.height);
  glUniform4f(u.margin, job_.margin_x, job_.margin_x, job_.margin_y, job_.margin_y);
  glUniform2fv(u.shape, FlamePose::kShapeRows + 1, pose.shape.data());
  glUniform1f(u.base, pose.base);
  glUniform1f(u.height, pose.height_factor);
  glUniform1i(u.deform, pose.deform ? 1 : 0);
  glUniform4f(u.sprite_rect, static_cast<float>(job_.sprite_x), static_cast<float>(job_.sprite_y),
              static_cast<float>(job_.sprite_w), static_cast<float>(job_.sprite_h));
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, batch_->sprite_atlas());
  glUniform1i(u.sprite, 0);
  glUniform1f(u.light, pose.light);
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_2D, batch_->cells_atlas());
  glUniform1i(u.cells, 1);
  glUniform1i(u.cells_row, job_.cells_y);
  glActiveTexture(GL_TEXTURE0);
  glDisable(GL_DEPTH_TEST);
  glDepthMask(GL_FALSE);
  glEnable(GL_BLEND);
  glBlendEquation(GL_FUNC_ADD);
  glBlendFunc(GL_ONE, GL_ONE);
  glBindVertexArray(batch_->grid_vao());
  glDrawArrays(GL_TRIANGLES, 0, batch_->grid_vertices());
  glBindVertexArray(0);
  glDisable(GL_BLEND);
  glDepthMask(GL_TRUE);
  glActiveTexture(GL_TEXTURE0);
}

// ---------------------------------------------------------------------------

EigenBatch::EigenBatch() {
  glow_ = Program::from_library("fullscreen.vert", "eigenflame_glow.frag");
  ug_.source = glow_.uniform("u_source");
  ug_.map = glow_.uniform("u_map");
  ug_.step = glow_.uniform("u_step");
  ug_.taps = glow_.uniform("u_taps");
  ug_.offset = glow_.uniform("u_offset");
  ug_.weight = glow_.uniform("u_weight");
  ug_.clamp_rect = glow_.uniform("u_src_rect");
  ug_.mask = glow_.uniform("u_mask");
  flame_ =
      Program::from_library("eigenflame.vert", "eigenflame.frag",
                            "#define SHAPE_ROWS " + std::to_string(FlamePose::kShapeRows) +
                                "\n#define GRID_COLUMNS " + std::to_string(kGridColumns) + "\n");
  const auto u = [&](const char* n) { return flame_.uniform(n); };
  uf_ = {u("u_view_projection"), u("u_origin"), u("u_right"),  u("u_size"),     u("u_margin"),
         u("u_shape"),           u("u_base"),   u("u_height"), u("u_deform"),   u("u_sprite"),
         u("u_sprite_rect"),     u("u_light"),  u("u_cells"),  u("u_cells_row")};
  cells_program_ = Program::from_library("fullscreen.vert", "eigenflame_cells.frag");
  uc_ = {cells_program_.uniform("u_sprite"), cells_program_.uniform("u_sprite_rect"),
         cells_program_.uniform("u_origin"), cells_program_.uniform("u_cells")};
  sprite_program_ = Program::from_library("fullscreen.vert", "eigenflame_sprite.frag");
  const auto v = [&](const char* n) { return sprite_program_.uniform(n); };
  us_ = {v("u_gray"),      v("u_glow"),      v("u_ramp"),       v("u_gray_rect"),
         v("u_glow_rect"), v("u_margin"),    v("u_brightness"), v("u_glow_strength"),
         v("u_glow_tint"), v("u_edge_fade"), v("u_foot_fade")};

  // The billboard grid: kGridColumns x kShapeRows cells over the glow-padded
  // area, two triangles a cell, each vertex with its cell's index (a cell
  // whose sprite is black is left out: eigenflame.vert).
  std::vector<float> verts;
  const int rows = FlamePose::kShapeRows;
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < kGridColumns; ++c) {
      const auto cell = static_cast<float>(r * kGridColumns + c);
      const auto put = [&](int cc, int rr) {
        verts.insert(verts.end(),
                     {static_cast<float>(cc) / kGridColumns, static_cast<float>(rr) / rows, cell});
      };
      put(c, r), put(c + 1, r), put(c, r + 1);
      put(c, r + 1), put(c + 1, r), put(c + 1, r + 1);
    }
  grid_vertices_ = static_cast<GLsizei>(verts.size() / 3);
  grid_vao_ = make_vertex_array();
  grid_vbo_ = make_buffer();
  glBindVertexArray(grid_vao_.get());
  glBindBuffer(GL_ARRAY_BUFFER, grid_vbo_.get());
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(verts.size() * sizeof(float)), verts.data(),
               GL_STATIC_DRAW);
  const GLint loc = glGetAttribLocation(flame_.id(), "a_grid");
  glEnableVertexAttribArray(static_cast<GLuint>(loc));
  glVertexAttribPointer(static_cast<GLuint>(loc), 2, GL_FLOAT, GL_FALSE, 3 * sizeof(float),
                        nullptr);
  const GLint cell_loc = glGetAttribLocation(flame_.id(), "a_cell");
  glEnableVertexAttribArray(static_cast<GLuint>(cell_loc));
  glVertexAttribPointer(static_cast<GLuint>(cell_loc), 1, GL_FLOAT, GL_FALSE, 3 * sizeof(float),
                        reinterpret_cast<const void*>(2 * sizeof(float)));
  glBindVertexArray(0);
  fullscreen_vao_ = make_vertex_array();
}

std::shared_ptr<EigenReconstructor> EigenBatch::reconstructor(const ImageStack& mean,
                                                              const ImageStack& eigen,
                                                              StackLayout layout,
                                                              int max_components) {
  std::erase_if(reconstructors_,
                [](const SharedReconstructor& r) { return r.reconstructor.expired(); });
  for (const SharedReconstructor& r : reconstructors_)
    if (r.mean == mean.data && r.eigen == eigen.data && r.layout == layout &&
        r.max_components == max_components)
      return r.reconstructor.lock();
  auto made = std::make_shared<EigenReconstructor>(mean, eigen, layout, max_components);
  reconstructors_.push_back({mean.data, eigen.data, layout, max_components, made});
  return made;
}

void EigenBatch::add(EigenSpriteJob* job) {
  members_.push_back(job);
  laid_out_ = false;
}

void EigenBatch::remove(EigenSpriteJob* job) {
  members_.erase(std::remove(members_.begin(), members_.end(), job), members_.end());
  laid_out_ = false;
}

void EigenBatch::layout() {
  // Shelf packing, 2 texels apart so filtering never reads a neighbour.
  constexpr int kGap = 2, kMaxRow = 2048;
  auto pack = [&](auto size_of, auto place, int& atlas_w, int& atlas_h) {
    int x = 0, y = 0, shelf = 0;
    atlas_w = atlas_h = 1;
    for (EigenSpriteJob* j : members_) {
      const auto [w, h] = size_of(*j);
      if (x > 0 && x + w > kMaxRow) x = 0, y += shelf + kGap, shelf = 0;
      place(*j, x, y);
      atlas_w = std::max(atlas_w, x + w);
      atlas_h = std::max(atlas_h, y + h);
      shelf = std::max(shelf, h);
      x += w + kGap;
    }
  };
  int gray_w = 0, gray_h = 0, glow_w = 0, glow_h = 0, sprite_w = 0, sprite_h = 0;
  pack(
      [](const EigenSpriteJob& j) {
        return std::pair{j.recon->width(), j.recon->height()};
      },
      [](EigenSpriteJob& j, int x, int y) { j.gray_x = x, j.gray_y = y; }, gray_w, gray_h);
  pack(
      [](const EigenSpriteJob& j) {
        return std::pair{j.glow_w, j.glow_h};
      },
      [](EigenSpriteJob& j, int x, int y) { j.glow_x = x, j.glow_y = y; }, glow_w, glow_h);
  pack(
      [](const EigenSpriteJob& j) {
        return std::pair{j.sprite_w, j.sprite_h};
      },
      [](EigenSpriteJob& j, int x, int y) { j.sprite_x = x, j.sprite_y = y; }, sprite_w, sprite_h);
  gray_ = RenderTarget::checked(gray_w, gray_h, "eigenflame: reconstruction atlas");
  glow_a_ = RenderTarget::checked(glow_w, glow_h, "eigenflame: glow atlas");
  glow_b_ = RenderTarget::checked(glow_w, glow_h, "eigenflame: glow atlas");
  sprite_ = RenderTarget::checked(sprite_w, sprite_h, "eigenflame: sprite atlas");
  int cells_rows = 0;
  for (EigenSpriteJob* j : members_) j->cells_y = cells_rows, cells_rows += FlamePose::kShapeRows;
  cells_ = RenderTarget::checked(kGridColumns, std::max(1, cells_rows), "eigenflame: cells atlas");
  for (EigenSpriteJob* j : members_) j->drawn_valid = false;  // new atlases: draw everyone
  laid_out_ = true;
}

void EigenBatch::render() {
  // First: layout() binds the atlases it makes, and the caller's framebuffer
  // (the studio's view, the scene's screen) must be the one given back.
  const FramebufferRestore caller;
  if (!laid_out_) layout();
  // Only flames whose weights differ from those their sprite shows (the
  // output depends on nothing else that changes): with a model frame held
  // between its 30 fps steps, most frames redraw few flames or none.
  bool any = false;
  for (EigenSpriteJob* j : members_) {
    const size_t n = std::min(j->weights.size(), static_cast<size_t>(j->recon->components()));
    j->redraw = !j->drawn_valid ||
                !std::equal(j->weights.begin(), j->weights.begin() + n, j->drawn.begin());
    if (j->redraw) std::copy_n(j->weights.begin(), n, j->drawn.begin());
    j->drawn_valid = true;
    any = any || j->redraw;
  }
  if (!any) return;
  // 1. Every flame's reconstruction into the gray atlas: from its frame
  // cache where it has one (first filling the frame's layer if new).
  for (EigenSpriteJob* j : members_)
    if (j->redraw && j->recon->caches()) j->recon->cache_frame(j->frame);
  gray_.bind();
  for (EigenSpriteJob* j : members_)
    if (j->redraw) j->recon->draw_near_frame_at(j->weights, j->frame, j->gray_x, j->gray_y);
  // 2. Glow, horizontal then vertical, each flame in its own region.
  glow_.use();
  glUniform1i(ug_.source, 0);
  glBindVertexArray(fullscreen_vao_.get());
  for (int pass = 0; pass < 2; ++pass) {
    (pass == 0 ? glow_a_ : glow_b_).bind();
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, pass == 0 ? gray_.texture() : glow_a_.texture());
    glUniform1i(ug_.mask, pass == 0 ? 1 : 0);
    for (EigenSpriteJob* j : members_) {
      if (j->glow_strength <= 0 || !j->redraw) continue;
      glViewport(j->glow_x, j->glow_y, j->glow_w, j->glow_h);
      glUniform1i(ug_.taps, j->taps);
      glUniform1fv(ug_.offset, j->taps, j->tap_offset.data());
      glUniform1fv(ug_.weight, j->taps, j->tap_weight.data());
      if (pass == 0) {  // from the gray image (flame uv), one glow texel per step
        const float mx = j->margin_x, my = j->margin_y;
        glUniform4f(ug_.map, 1 + 2 * mx, 1 + 2 * my, -mx, -my);
        glUniform2f(ug_.step, (1 + 2 * mx) / j->glow_w, 0.0f);
        glUniform4f(ug_.clamp_rect, static_cast<float>(j->gray_x), static_cast<float>(j->gray_y),
                    static_cast<float>(j->recon->width()), static_cast<float>(j->recon->height()));
      } else {
        glUniform4f(ug_.map, 1, 1, 0, 0);
        glUniform2f(ug_.step, 0.0f, 1.0f / j->glow_h);
        glUniform4f(ug_.clamp_rect, static_cast<float>(j->glow_x), static_cast<float>(j->glow_y),
                    static_cast<float>(j->glow_w), static_cast<float>(j->glow_h));
      }
      glDrawArrays(GL_TRIANGLES, 0, 3);
    }
  }
  // 3. Each flame's finished sprite: coloured flame + glow.
  sprite_.bind();
  sprite_program_.use();
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, gray_.texture());
  glUniform1i(us_.gray, 0);
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_2D, glow_b_.texture());
  glUniform1i(us_.glow, 1);
  glUniform1i(us_.ramp, 2);
  glActiveTexture(GL_TEXTURE2);
  for (EigenSpriteJob* j : members_) {
    if (!j->redraw) continue;
    glViewport(j->sprite_x, j->sprite_y, j->sprite_w, j->sprite_h);
    glBindTexture(GL_TEXTURE_2D, j->ramp);
    glUniform4f(us_.gray_rect, static_cast<float>(j->gray_x), static_cast<float>(j->gray_y),
                static_cast<float>(j->recon->width()), static_cast<float>(j->recon->height()));
    glUniform4f(us_.glow_rect, static_cast<float>(j->glow_x), static_cast<float>(j->glow_y),
                static_cast<float>(j->glow_w), static_cast<float>(j->glow_h));
    glUniform2f(us_.margin, j->margin_x, j->margin_y);
    glUniform1f(us_.brightness, j->brightness);
    glUniform1f(us_.glow_strength, j->glow_strength);
    glUniform3f(us_.glow_tint, j->glow_tint.x, j->glow_tint.y, j->glow_tint.z);
    glUniform1f(us_.edge_fade, j->edge_fade);
    glUniform2f(us_.foot_fade, j->foot_fade[0], j->foot_fade[1]);
    glDrawArrays(GL_TRIANGLES, 0, 3);
  }
  // 4. Which cells of each billboard add any light.
  cells_.bind();
  cells_program_.use();
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, sprite_.texture());
  glUniform1i(uc_.sprite, 0);
  glUniform2f(uc_.cells, static_cast<float>(kGridColumns),
              static_cast<float>(FlamePose::kShapeRows));
  glBindVertexArray(fullscreen_vao_.get());
  for (EigenSpriteJob* j : members_) {
    if (!j->redraw) continue;
    glViewport(0, j->cells_y, kGridColumns, FlamePose::kShapeRows);
    glUniform4f(uc_.sprite_rect, static_cast<float>(j->sprite_x), static_cast<float>(j->sprite_y),
                static_cast<float>(j->sprite_w), static_cast<float>(j->sprite_h));
    glUniform2i(uc_.origin, 0, j->cells_y);
    glDrawArrays(GL_TRIANGLES, 0, 3);
  }
  glActiveTexture(GL_TEXTURE0);
}

std::array<uint8_t, 256 * 4> transfer_ramp(std::span<const Vec3> stops, float black,
                                           std::span<const float> positions) {
  std::array<uint8_t, 256 * 4> r{};
  const size_t n = stops.size();
  const bool placed = positions.size() == n;
  for (int i = 0; i < 256; ++i) {
    size_t a = 0;
    float t = 0;
    if (!placed) {
      const double x = ramp_lightness(i, black) * static_cast<double>(n - 1);
      a = std::min(n - 2, static_cast<size_t>(x));
      t = static_cast<float>(x - a);
    } else {
      const double x = ramp_lightness(i, black);
      while (a + 2 < n && x >= positions[a + 1]) ++a;  // the stretch [a, a + 1] holding x
      const double lo = positions[a], hi = positions[a + 1];
      t = x <= lo ? 0.0f : x >= hi ? 1.0f : static_cast<float>((x - lo) / (hi - lo));
    }
    const Vec3 c = stops[a] * (1 - t) + stops[a + 1] * t;
    const float v[3] = {c.x, c.y, c.z};
    for (int k = 0; k < 3; ++k)
      r[static_cast<size_t>(i) * 4 + k] =
          static_cast<uint8_t>(std::lround(std::clamp(v[k], 0.0f, 1.0f) * 255));
    r[static_cast<size_t>(i) * 4 + 3] = 255;
  }
  return r;
}

}  // namespace candela
