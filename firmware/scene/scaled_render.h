// Drawing a scene at a reduced size and scaling it up to the screen. A
// fireplace's detail (flames from 128x160 model images, soft light) needs
// far fewer pixels than a 1920x1080 screen has, and a Pi-class GPU (or
// llvmpipe) pays for every pixel every pass: drawn at 960x540, the eigen
// fireplace's passes cost about two fifths of what they cost at 1920x1080,
// and one pass scales the result up. A scene asks for it with [display]
// render_scale and render_max_height (scene/scene_file.h); the elements do
// not know: they draw into the reduced target as if it were the screen.
#pragma once

#include "gl/program.h"
#include "gl/render_target.h"
#include "gl/texture.h"

namespace candela {

struct RenderSize {
  int width = 0, height = 0;
  bool operator==(const RenderSize&) const = default;
};

// The size a scene is drawn at on a `screen`: `scale` (0.25 to 1) of each
// side, and at most `max_height` rows (0: no limit); never more than the
// screen, never under 1x1. The screen's own size when neither reduces it.
RenderSize scaled_render_size(RenderSize screen, float scale, int max_height);

class ScaledRender {
 public:
  ScaledRender(float scale, int max_height) : scale_(scale), max_height_(max_height) {}
  // The screen's own size where neither limit reduces it (then no GL work).
  RenderSize size_for(RenderSize screen) const {
    return scaled_render_size(screen, scale_, max_height_);
  }
  // Binds a target of `size` (made, with depth, on first use and when the
  // size changes) with its whole area as viewport. Returns its framebuffer.
  GLuint begin(RenderSize size);
  // Draws the target onto the bound framebuffer, filling the viewport.
  void finish();

 private:
  float scale_;
  int max_height_;
  RenderSize size_;
  RenderTarget target_;
  Renderbuffer depth_;
  Program program_;
  VertexArray vao_;
  GLint u_image_ = -1;
};

}  // namespace candela
