// Eigen views of a loaded model's tensors (tools only).
#pragma once

#include <Eigen/Dense>

#include "model/flame_model.h"
#include "transitions.h"

namespace candela::tools {

inline Eigen::MatrixXf model_weights(const model::FlameModel& m) {
  return Eigen::Map<const Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
      m.weights.data(), m.frames(), m.components());
}

inline WeightSpace model_space(const model::FlameModel& m, int components = 0) {
  return WeightSpace::from(model_weights(m), m.clips, components);
}

}  // namespace candela::tools
