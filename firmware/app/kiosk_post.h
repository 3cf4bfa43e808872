// The kiosk's last pass over a frame (app/frame_loop.cpp): the cross-fade
// from the old scene's last frame and the master brightness, one
// full-screen triangle each, blended over the frame. Made once (it compiles
// its program; needs the GL context): nothing allocates per frame. The
// cross-fade's target is made at a scene swap, itself a rebuild.
#pragma once

#include <algorithm>

#include "gl/program.h"
#include "gl/render_target.h"
#include "gl/texture.h"

namespace candela {

// What KioskPost draws, frame by frame: the brightness shown glides to the
// kiosk's target, the whole range in a quarter second (no flash, no lag);
// a cross-fade runs down over its seconds.
struct BrightnessGlide {
  float level = 1.0f;        // the brightness shown
  float fade_left_s = 0.0f;  // of the cross-fade

  void step(float seconds, float target) {
    level += std::clamp(target - level, -4.0f * seconds, 4.0f * seconds);
    fade_left_s = std::max(0.0f, fade_left_s - seconds);
  }
  // The old frame's opacity over a cross-fade of `crossfade_s` (0: none).
  float old_alpha(float crossfade_s) const {
    return crossfade_s > 0 ? fade_left_s / crossfade_s : 0.0f;
  }
};

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
