// RAII wrappers for GL objects, so elements own their GPU resources.
#pragma once

#include <cstdint>
#include <utility>

#include "gl/gles.h"

namespace candela {

template <void (*Delete)(GLsizei, const GLuint*)>
class GlHandle {
 public:
  GlHandle() = default;
  explicit GlHandle(GLuint id) : id_(id) {}
  GlHandle(GlHandle&& o) noexcept : id_(std::exchange(o.id_, 0)) {}
  GlHandle& operator=(GlHandle&& o) noexcept {
    if (this != &o) {
      reset();
      id_ = std::exchange(o.id_, 0);
    }
    return *this;
  }
  ~GlHandle() { reset(); }
  GLuint get() const { return id_; }
  void reset() {
    if (id_) Delete(1, &id_);
    id_ = 0;
  }

 private:
  GLuint id_ = 0;
};

namespace gl_detail {
inline void del_tex(GLsizei n, const GLuint* p) { glDeleteTextures(n, p); }
inline void del_buf(GLsizei n, const GLuint* p) { glDeleteBuffers(n, p); }
inline void del_vao(GLsizei n, const GLuint* p) { glDeleteVertexArrays(n, p); }
inline void del_fbo(GLsizei n, const GLuint* p) { glDeleteFramebuffers(n, p); }
inline void del_rbo(GLsizei n, const GLuint* p) { glDeleteRenderbuffers(n, p); }
}  // namespace gl_detail

using Texture = GlHandle<gl_detail::del_tex>;
using Buffer = GlHandle<gl_detail::del_buf>;
using VertexArray = GlHandle<gl_detail::del_vao>;
using Framebuffer = GlHandle<gl_detail::del_fbo>;
using Renderbuffer = GlHandle<gl_detail::del_rbo>;

inline Texture make_texture() {
  GLuint id = 0;
  glGenTextures(1, &id);
  return Texture(id);
}
inline Buffer make_buffer() {
  GLuint id = 0;
  glGenBuffers(1, &id);
  return Buffer(id);
}
inline VertexArray make_vertex_array() {
  GLuint id = 0;
  glGenVertexArrays(1, &id);
  return VertexArray(id);
}
inline Framebuffer make_framebuffer() {
  GLuint id = 0;
  glGenFramebuffers(1, &id);
  return Framebuffer(id);
}
inline Renderbuffer make_renderbuffer() {
  GLuint id = 0;
  glGenRenderbuffers(1, &id);
  return Renderbuffer(id);
}

// An RGBA8 texture from tightly packed pixels (rows top to bottom).
Texture upload_rgba8(int width, int height, const uint8_t* pixels, bool linear = true);

}  // namespace candela
