// Offscreen drawing: a texture with the framebuffer that draws into it, and a
// scope that puts back the framebuffer and viewport it found.
#pragma once

#include <array>
#include <string>

#include "gl/texture.h"

namespace candela {

// An RGBA8 colour texture (linear filtering, clamped to its edge) and a
// framebuffer drawing into it. Elements render into one in prepare()
// (scene/element.h) and read it in their draw passes.
class RenderTarget {
 public:
  RenderTarget() = default;
  // Makes the texture and framebuffer; leaves the framebuffer bound. Check
  // complete() (or use checked()) before drawing into it.
  RenderTarget(int width, int height);
  // As above, but throws RuntimeError("<what>: framebuffer incomplete (WxH)").
  static RenderTarget checked(int width, int height, const std::string& what);

  bool complete() const { return complete_; }
  GLuint texture() const { return texture_.get(); }
  GLuint framebuffer() const { return framebuffer_.get(); }
  int width() const { return width_; }
  int height() const { return height_; }
  explicit operator bool() const { return framebuffer_.get() != 0; }
  // Binds the framebuffer; the viewport is the caller's to set.
  void bind() const;

 private:
  Texture texture_;
  Framebuffer framebuffer_;
  int width_ = 0, height_ = 0;
  bool complete_ = false;
};

// A 24-bit depth renderbuffer of width x height, attached to the bound
// framebuffer (whose completeness the caller checks once it is whole).
Renderbuffer attach_depth_buffer(int width, int height);

// Remembers the bound draw framebuffer and the viewport, and binds and sets
// them again when it goes out of scope: for code that may be called with any
// framebuffer bound (tools, tests; a scene's prepare stage re-binds the
// screen itself).
class FramebufferRestore {
 public:
  FramebufferRestore();
  ~FramebufferRestore();
  FramebufferRestore(const FramebufferRestore&) = delete;
  FramebufferRestore& operator=(const FramebufferRestore&) = delete;

 private:
  GLint framebuffer_ = 0;
  std::array<GLint, 4> viewport_{};
};

}  // namespace candela
