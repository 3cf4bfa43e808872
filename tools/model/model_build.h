// `candela-tool build`: dataset -> EigenFires PCA + motion graph (+ Learning
// Flames, when enabled) -> one model file, plus the reports.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "dataset.h"
#include "learning_flames.h"
#include "model/model_writer.h"
#include "pca.h"
#include "transitions.h"

namespace candela::tools {

struct BuildOptions {
  PcaOptions pca;
  int holdout_every = 10;  // every n-th frame is left out of the fit (0: none); still in the model
  model::DType eigen_dtype = model::DType::kU16;
  MotionGraphOptions graph;
  model::ColourDefaults colour;
  bool learning_flames = true;
  LearningFlamesOptions flames;
  nlohmann::json provenance_options = nlohmann::json::object();
  std::function<void(const std::string&)> progress;
};

struct PsnrRow {
  int components;
  double train_db, holdout_db;
};

struct BuiltModel {
  PcaResult pca;
  MotionGraphData graph;
  std::vector<int> holdout;
  std::vector<PsnrRow> psnr;  // reconstruction PSNR versus E
  model::ModelWriter writer;
  bool has_flames = false;
  LearningFlamesModel flames;
  // Held-out PSNR at an equal number of parameters per frame (np + nw + 1 + ne):
  // plain EigenFires versus the shape-normalised Learning Flames model.
  double plain_equal_db = 0, flames_equal_db = 0;
  int equal_params = 0;
  float black_level = 0;  // written to the model's colour (see build_model)
};

// Throws BuildOptionError, before any work, for options whose model the
// runtime would refuse (FlameModel::from's limits), and std::runtime_error if
// the model built fails the runtime's validation anyway (e.g. a clip's fps):
// what it returns is a model that `candela` loads and plays.
BuiltModel build_model(const Dataset& d, const BuildOptions& opt);
// A build option the runtime's limits refuse; the message names the option.
struct BuildOptionError : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};
void check_build_options(const BuildOptions& opt);
// psnr.txt + psnr.png (PSNR vs E: axes, ticks, titles, legend), eigenfires.png
// (the mean and first eigen-images, each named), trajectory.png (the first
// three weights from three viewpoints, a legend of the clips); text in
// Canvas::text's 5x7 font.
void write_reports(const Dataset& d, const BuiltModel& m, const std::string& dir);
std::string tool_version();

}  // namespace candela::tools
