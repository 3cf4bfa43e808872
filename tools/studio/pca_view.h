// The 3-D PCA view: each clip's track through the first three weights in its
// own colour (and a story's own path, transitions included), the flame's
// current weights as a moving marker. Drawn with ImGui's draw list through
// its own small orthographic-with-a-little-perspective projection; drag
// rotates, the wheel zooms, a click picks the nearest frame.
#pragma once

#include <imgui.h>

#include <vector>

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
  // Draws into [origin, origin + size) of `list`; remembers where for pick().
  void draw(ImDrawList* list, ImVec2 origin, ImVec2 size, const Session& session);
  // The model frame drawn nearest to `point` (canvas pixels from the top
  // left), within 12 pixels; -1: none.
  int pick(ImVec2 point) const;

 private:
  struct P3 {
    float x, y, z;
  };
  ImVec2 project(P3 p) const;
  P3 of_weights(const float* w) const;
  std::vector<P3> points_;      // per model frame
  std::vector<int> clip_;       // per model frame
  std::vector<ImVec2> screen_;  // per model frame, as last drawn (canvas pixels)
  float norm_ = 1;
  int dims_ = 0;
  float yaw_ = 0.6f, pitch_ = 0.35f, zoom_ = 1.0f;
  ImVec2 origin_{}, size_{1, 1};
};

}  // namespace candela::studio
