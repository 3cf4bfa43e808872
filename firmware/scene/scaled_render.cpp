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

void ScaledRender::finish() {
  program_.use();
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, target_.texture());
  glUniform1i(u_image_, 0);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glDisable(GL_SCISSOR_TEST);
  glBindVertexArray(vao_.get());
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);
}

}  // namespace candela
