#include "scene/scaled_render.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace candela {

RenderSize scaled_render_size(RenderSize screen, float scale, int max_height) {
  double s = std::clamp(static_cast<double>(scale), 0.0, 1.0);
  if (max_height > 0 && screen.height > 0)
    s = std::min(s, static_cast<double>(max_height) / screen.height);
  if (s >= 1.0) return screen;
  return {std::max(1, static_cast<int>(std::lround(screen.width * s))),
          std::max(1, static_cast<int>(std::lround(screen.height * s)))};
}

bool project_box(const Box3& box, const Mat4& view_projection, RenderSize size, PixelBox& out) {
  out = {};
  if (box.empty()) return true;
  float x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
  for (int i = 0; i < 8; ++i) {
    const Vec4 c =
        view_projection * Vec4{(i & 1) ? box.hi.x : box.lo.x, (i & 2) ? box.hi.y : box.lo.y,
                               (i & 4) ? box.hi.z : box.lo.z, 1.0f};
    if (!(c.w > 1e-4f)) return false;  // at or behind the camera (or NaN)
    x0 = std::min(x0, c.x / c.w);
    x1 = std::max(x1, c.x / c.w);
    y0 = std::min(y0, c.y / c.w);
    y1 = std::max(y1, c.y / c.w);
  }
  // Normalised device coordinates to pixels, outwards, within the target
  // (clamped as floats first: a corner near the camera's plane goes far out).
  const auto px = [](float ndc, int n) {
    return std::clamp((ndc + 1.0f) * 0.5f * static_cast<float>(n), -1.0f, n + 1.0f);
  };
  out.x0 = std::max(0, static_cast<int>(std::floor(px(x0, size.width))));
  out.y0 = std::max(0, static_cast<int>(std::floor(px(y0, size.height))));
  out.x1 = std::min(size.width, static_cast<int>(std::ceil(px(x1, size.width))));
  out.y1 = std::min(size.height, static_cast<int>(std::ceil(px(y1, size.height))));
  if (out.empty()) out = {};
  return true;
}

PixelBox scaled_up_box(PixelBox drawn_box, RenderSize drawn, RenderSize full) {
  if (drawn_box.empty() || drawn.width <= 0 || drawn.height <= 0) return {};
  // A screen pixel at x reads the reduced pixels around (x + 0.5) * w / W - 0.5:
  // two reduced pixels' margin keeps every lookup outside the box on plain
  // background.
  const auto lo = [](int v, int n, int big) {
    return std::max(0, static_cast<int>(std::floor((v - 2.0) * big / n)));
  };
  const auto hi = [](int v, int n, int big) {
    return std::min(big, static_cast<int>(std::ceil((v + 2.0) * big / n)));
  };
  return {lo(drawn_box.x0, drawn.width, full.width), lo(drawn_box.y0, drawn.height, full.height),
          hi(drawn_box.x1, drawn.width, full.width), hi(drawn_box.y1, drawn.height, full.height)};
}

GLuint ScaledRender::begin(RenderSize size) {
  if (!target_ || size != size_) {
    target_ = RenderTarget::checked(size.width, size.height, "scene at a reduced size");
    depth_ = attach_depth_buffer(size.width, size.height);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw RuntimeError("scene at a reduced size: framebuffer with depth incomplete");
    size_ = size;
  }
  if (program_.id() == 0) {
    program_ = Program::from_library("fullscreen.vert", "scene_upscale.frag");
    u_image_ = program_.uniform("u_image");
    vao_ = make_vertex_array();
  }
  target_.bind();
  glViewport(0, 0, size.width, size.height);
  return target_.framebuffer();
}

void ScaledRender::finish(RenderSize full, PixelBox content, Vec3 background) {
  scaled_up_ = scaled_up_box(content, size_, full);
  const bool whole = scaled_up_ == PixelBox{0, 0, full.width, full.height};
  glDisable(GL_SCISSOR_TEST);
  if (!whole) {
    glClearColor(background.x, background.y, background.z, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    if (scaled_up_.empty()) return;
    glEnable(GL_SCISSOR_TEST);
    glScissor(scaled_up_.x0, scaled_up_.y0, scaled_up_.x1 - scaled_up_.x0,
              scaled_up_.y1 - scaled_up_.y0);
  }
  program_.use();
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, target_.texture());
  glUniform1i(u_image_, 0);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glBindVertexArray(vao_.get());
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);
  glDisable(GL_SCISSOR_TEST);
}

}  // namespace candela
