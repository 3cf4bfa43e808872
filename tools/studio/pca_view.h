// The 3-D PCA view: each clip's track through the first three weights in its
// own colour (and a story's own path, transitions included), the flame's
// current weights as a moving marker. Drawn with ImGui's draw list through
// its own small orthographic-with-a-little-perspective projection; drag
// rotates, the wheel zooms, a click picks the nearest frame.
#pragma once

#include <imgui.h>

#include <memory>
#include <vector>

#include "gl/texture.h"

namespace candela::studio {

class Session;

class PcaView {
 public:
  explicit PcaView(const Session& session);
  void rotate(float dx_pixels, float dy_pixels);
  void zoom(float wheel_steps);
  float yaw() const { return yaw_; }
  float pitch() const { return pitch_; }
  float scale() const { return zoom_; }
  // Draws into [origin, origin + size) of `list` (between ImGui::NewFrame and
  // Render; a changed view redraws its cached tracks texture with GL then);
  // remembers where for pick().
  void draw(ImDrawList* list, ImVec2 origin, ImVec2 size, const Session& session);
  // The model frame drawn nearest to `point` (canvas pixels from the top
  // left), within 12 pixels; -1: none.
  int pick(ImVec2 point) const;
  // Where model frame f was last drawn (canvas pixels); (-1, -1): nowhere.
  ImVec2 screen_of(int f) const {
    return f >= 0 && static_cast<size_t>(f) < screen_.size() ? screen_[static_cast<size_t>(f)]
                                                             : ImVec2(-1, -1);
  }

 private:
  struct P3 {
    float x, y, z;
  };
  ImVec2 project(P3 p) const;                // canvas pixels
  void draw_tracks(const Session& session);  // into the cached texture
  P3 of_weights(const float* w) const;
  std::vector<P3> points_;      // per model frame
  std::vector<int> clip_;       // per model frame
  std::vector<ImVec2> screen_;  // per model frame, as last drawn (canvas pixels)
  // The tracks change only when the view does: drawn (by ImGui's own
  // renderer) into a texture then, which each frame shows under the markers.
  std::unique_ptr<ImDrawList> cache_list_;
  Texture cache_;
  Framebuffer cache_fbo_;
  float cached_yaw_ = -1e9f, cached_pitch_ = 0, cached_zoom_ = 0;
  ImVec2 cached_size_{};
  float norm_ = 1;
  int dims_ = 0;
  float yaw_ = 0.6f, pitch_ = 0.35f, zoom_ = 1.0f;
  ImVec2 origin_{}, size_{1, 1};
};

}  // namespace candela::studio
