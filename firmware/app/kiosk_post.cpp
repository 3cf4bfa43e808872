#include "app/kiosk_post.h"

#include <algorithm>

#include "gl/gles.h"

namespace candela {

KioskPost::KioskPost()
    : program_(Program::from_library("fullscreen.vert", "kiosk_post.frag")),
      vao_(make_vertex_array()) {
  u_textured_ = program_.uniform("u_textured");
  u_alpha_ = program_.uniform("u_alpha");
  u_image_ = program_.uniform("u_image");
}

RenderTarget& KioskPost::snapshot_target(int w, int h) {
  if (!old_ || old_.width() != w || old_.height() != h) old_ = RenderTarget(w, h);
  return old_;
}

void KioskPost::draw(float old_alpha, float level) {
  const bool fade = old_alpha > 0.0f && old_;
  const bool dim = level < 0.999f;
  if (!fade && !dim) return;
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  glEnable(GL_BLEND);
  // Colour only: the frame's alpha stays as drawn (a dimmed frame read back
  // had alpha 191 at brightness 0.5, and PNG viewers showed it washed out).
  glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ZERO, GL_ONE);
  program_.use();
  glBindVertexArray(vao_.get());
  if (fade) {
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, old_.texture());
    glUniform1i(u_image_, 0);
    glUniform1i(u_textured_, 1);
    glUniform1f(u_alpha_, old_alpha);
    glDrawArrays(GL_TRIANGLES, 0, 3);
  }
  if (dim) {
    glUniform1i(u_textured_, 0);
    glUniform1f(u_alpha_, 1.0f - std::clamp(level, 0.0f, 1.0f));
    glDrawArrays(GL_TRIANGLES, 0, 3);
  }
  glBindVertexArray(0);
  glDisable(GL_BLEND);
}

}  // namespace candela
