// Learning Flames' inverse normalisation for the vertex stage. A state x
// holds path[np] (flame centre x, pixels of the model's frames) and
// width[nw] (2 x the slice's x standard deviation, pixels) sampled at
// heights (i + 0.5) / n from base to tip, then the flame's height (pixels),
// then the appearance weights. Path and width are interpolated with natural
// cubic splines (linear beyond the end samples, as the model builder does)
// at the billboard's grid rows; the vertex shader places each row's span of
// the normalised image (+-span slice widths around the path) there.
#pragma once

#include <array>
#include <span>

#include "elements/eigenflame/eigen_renderer.h"

namespace candela {

namespace model {
class FlameModel;
}

// Natural cubic spline through n <= kMax samples at t_i = (i + 0.5) / n,
// linear beyond the ends. Fixed size: no allocation.
class SampledSpline {
 public:
  static constexpr int kMax = 64;
  void fit(std::span<const float> v);
  float operator()(float t) const;

 private:
  int n_ = 0;
  std::array<float, kMax> v_{}, m_{};
};

class FlameShapeModel {
 public:
  static FlameShapeModel from(const model::FlameModel& m);
  int dim() const { return np_ + nw_ + 1 + ne_; }
  int np() const { return np_; }
  int nw() const { return nw_; }
  // Fills pose.shape / base / height_factor from state x. `bend`: extra path
  // offset at the tip in flame-image heights (wind), growing linearly with height.
  void pose(std::span<const float> x, float bend, FlamePose& pose) const;

  int np_ = 10, nw_ = 10, ne_ = 5;
  float frame_w_ = 1, frame_h_ = 1;  // model frame size, pixels
  float base_y_ = 0;                 // base row in the model frame, pixels from the top
  float span_ = 2.5f;                // normalised image: +-span slice widths
};

}  // namespace candela
