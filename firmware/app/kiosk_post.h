// The kiosk's last pass over a frame (app/frame_loop.cpp): the cross-fade
// from the old scene's last frame and the master brightness, one
// full-screen triangle each, blended over the frame. Made once (it compiles
// its program; needs the GL context): nothing allocates per frame. The
// cross-fade's target is made at a scene swap, itself a rebuild.
#pragma once

#include "gl/program.h"
#include "gl/render_target.h"
#include "gl/texture.h"

namespace candela {

class KioskPost {
 public:
  KioskPost();  // throws RuntimeError if the program does not build
  // A target of the screen's size to draw the old scene's last frame into.
  RenderTarget& snapshot_target(int w, int h);
  // Over the bound framebuffer: the old frame at `old_alpha` (0: none), then
  // black at 1 - level (level 1: nothing drawn).
  void draw(float old_alpha, float level);

 private:
  Program program_;
  VertexArray vao_;
  RenderTarget old_;
  GLint u_textured_ = -1, u_alpha_ = -1, u_image_ = -1;
};

}  // namespace candela
