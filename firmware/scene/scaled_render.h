// Drawing a scene at a reduced size and scaling it up to the screen. A
// fireplace's detail (flames from 128x160 model images, soft light) needs
// far fewer pixels than a 1920x1080 screen has, and a Pi-class GPU (or
// llvmpipe) pays for every pixel every pass: drawn at 960x540, the eigen
// fireplace's passes cost about two fifths of what they cost at 1920x1080,
// and one pass scales the result up. A scene asks for it with [display]
// render_scale and render_max_height (scene/scene_file.h); the elements do
// not know: they draw into the reduced target as if it were the screen.
#pragma once

#include "gl/math.h"
#include "gl/program.h"
#include "gl/render_target.h"
#include "gl/texture.h"

namespace candela {

struct RenderSize {
  int width = 0, height = 0;
  bool operator==(const RenderSize&) const = default;
};

// A rectangle of pixels, y up from the bottom as GL counts them: the columns
// x0..x1-1 of the rows y0..y1-1.
struct PixelBox {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  bool empty() const { return x1 <= x0 || y1 <= y0; }
  bool operator==(const PixelBox&) const = default;
};

// The pixels of a target of `size` that `box` (world space) can cover under
// `view_projection`, rounded outwards and clamped to the target (empty when
// it lies outside). False where part of the box lies at or behind the
// camera's plane: its picture has no bound there.
bool project_box(const Box3& box, const Mat4& view_projection, RenderSize size, PixelBox& out);

// The pixels of the `full` screen whose scaled-up colour can depend on the
// pixels `drawn_box` of the reduced picture (of size `drawn`): the box grown
// by the bilinear lookup's reach (two reduced pixels), scaled and clamped.
// Outside it, the screen shows only what lies outside drawn_box.
PixelBox scaled_up_box(PixelBox drawn_box, RenderSize drawn, RenderSize full);

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
  // Draws the target onto the bound framebuffer (of size `full`, the
  // viewport) scaled up. Only the pixels `content` of the target hold
  // anything but `background`: the screen outside their scaled-up box
  // (scaled_up_box) is cleared to `background` instead, the same colour a
  // scaled-up plain background gives, and the lookup runs only inside it.
  // On llvmpipe the lookup costs about 5 ns a screen pixel, the clear next
  // to nothing.
  void finish(RenderSize full, PixelBox content, Vec3 background);
  // The screen pixels the last finish() scaled up.
  PixelBox last_scaled_up() const { return scaled_up_; }

 private:
  float scale_;
  int max_height_;
  RenderSize size_;
  PixelBox scaled_up_;
  RenderTarget target_;
  Renderbuffer depth_;
  Program program_;
  VertexArray vao_;
  GLint u_image_ = -1;
};

}  // namespace candela
