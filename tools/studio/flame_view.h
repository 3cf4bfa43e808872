// The flame as the runtime shows it: the runtime's own EigenRenderer (same
// shaders, colour ramp and glow) drawn into an offscreen texture that the UI
// shows. The one file that touches EigenRenderer / EigenBatch.
#pragma once

#include <memory>
#include <span>
#include <vector>

#include "gl/gles.h"
#include "gl/render_target.h"
#include "gl/texture.h"
#include "look.h"

namespace candela {
struct EigenModel;
class EigenRenderer;
}  // namespace candela

namespace candela::studio {

struct PixelRect {
  int x = 0, y = 0, w = 0, h = 0;  // top-left origin
};

class FlameView {
 public:
  explicit FlameView(const EigenModel& model);
  ~FlameView();
  FlameView(const FlameView&) = delete;
  FlameView& operator=(const FlameView&) = delete;

  // Renders `weights` with `look` into a w x h texture (re-made on resize;
  // a changed look re-makes the renderer: its ramp and glow are fixed at
  // construction). Leaves the default framebuffer bound.
  void render(std::span<const float> weights, const Look& look, int w, int h);
  GLuint texture() const { return target_.texture(); }
  int width() const { return w_; }
  int height() const { return h_; }
  // Where the model's image lies in the texture (top-left origin, pixels).
  PixelRect image_rect() const { return image_; }

 private:
  const EigenModel& model_;
  std::unique_ptr<EigenRenderer> renderer_;
  Look look_{};
  bool have_look_ = false;
  std::vector<float> weights_;  // what the renderer reads at prepare()
  RenderTarget target_;
  int w_ = 0, h_ = 0;
  PixelRect image_;
};

}  // namespace candela::studio
