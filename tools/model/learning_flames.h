// Learning Flames (Stich & Magnor): a flame as np path + nw width samples +
// its height (the shape, from image moments per height slice) and ne
// eigenflame weights (the appearance of the shape-normalised flame).
#pragma once

#include <Eigen/Dense>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "arp.h"
#include "dataset.h"
#include "pca.h"

namespace candela::tools {

struct FlameShape {
  std::vector<double> path;   // np: centre x (pixels) at equidistant heights, base to tip
  std::vector<double> width;  // nw: 2 x the slice's x standard deviation (pixels)
  double height = 0;          // pixels from the base up to the tip
};

struct ShapeOptions {
  int np = 10, nw = 10;
  int norm_width = 48, norm_height = 80;  // normalised image size
  double base_row = -1;  // base y in pixels (default: the dataset's base_row x height)
  double span = 2.5;     // the normalised image covers +-span widths around the path
  double tip_fraction =
      0.02;  // rows with less than this share of the peak row mass are above the tip
};

// Natural cubic spline through (t_i, v_i), linear beyond the ends.
class CubicSpline {
 public:
  CubicSpline(std::vector<double> t, std::vector<double> v);
  double operator()(double t) const;

 private:
  std::vector<double> t_, v_, m_;  // m_: second derivatives
};

// Heights (0 = base, 1 = tip) where the n samples of a shape curve sit.
inline double sample_height(int i, int n) { return (i + 0.5) / n; }

FlameShape measure_shape(const uint8_t* frame, int width, int height, const ShapeOptions& o);
// Straightens and equalises the flame: normalised image (norm_width x norm_height, float 0..255).
void normalise(const uint8_t* frame, int width, int height, const FlameShape& s,
               const ShapeOptions& o, float* out);
// The inverse: the flame of shape s from a normalised image, into width x height.
void denormalise(const float* norm, const FlameShape& s, const ShapeOptions& o, int width,
                 int height, float* out);

struct LearningFlamesOptions {
  ShapeOptions shape;
  int ne = 5;
  bool learn_dynamics = true;
  ArpLearnOptions arp;
  std::vector<int> holdout;  // frames left out of the appearance PCA (still measured)
  std::function<void(const std::string&)> progress;
};

struct LearningFlamesModel {
  ShapeOptions shape;
  int ne = 5;
  std::vector<int> frames;  // dataset frames used (single plume)
  Eigen::MatrixXd params;   // frames.size() x (np + nw + 1 + ne)
  PcaResult appearance;     // PCA of the normalised frames
  ArpLearnResult dynamics;
  int dim() const { return shape.np + shape.nw + 1 + ne; }
  FlameShape shape_of(const Eigen::VectorXd& x) const;
  // Renders parameters x into a width x height gray image (0..255).
  void render(const Eigen::VectorXd& x, int width, int height, float* out) const;
};

// The dataset has single-plume frames, but no run of them long enough to
// learn the dynamics from: `build` then leaves the Learning Flames part out.
struct NoFlameSequence : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

LearningFlamesModel learn_flames(const Dataset& d, const LearningFlamesOptions& o);

}  // namespace candela::tools

namespace candela::model {
class FlameModel;
}

namespace candela::tools {
// The Learning Flames part of a loaded model file, ready to sample and render
// (appearance dequantised; the ARP in double). Throws if the model has none.
LearningFlamesModel flames_from_model(const model::FlameModel& m);
}  // namespace candela::tools
