// Writes a seed corpus for model_reader_fuzz: one small valid model.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "model/model_writer.h"

int main(int argc, char** argv) {
  if (argc < 2) return 2;
  namespace cm = candela::model;
  const int w = 4, h = 3, e = 2, f = 3;
  const size_t px = w * h;
  std::vector<float> mean(px, 20.0f), eig(e * px), weights(f * e, 1.0f), var{2.0f, 1.0f};
  for (size_t i = 0; i < eig.size(); ++i) eig[i] = std::sin(static_cast<float>(i));
  std::vector<int32_t> off{0, 1, 2, 3}, succ{1, 2, 0};
  std::vector<float> cost{1, 1, 1};
  cm::ModelWriter mw;
  mw.set_info(
      {{"kind", "eigenfires"},
       {"width", w},
       {"height", h},
       {"components", e},
       {"frames", f},
       {"total_variance", 3.0},
       {"graph", {{"theta_min", 0.1}}},
       {"clips",
        {{{"name", "c"},
          {"source", "s"},
          {"first", 0},
          {"count", f},
          {"fps", 30.0},
          {"labels", nlohmann::json::array()}}}},
       {"colour",
        {{"hue", 30.0}, {"saturation", 0.8}, {"glow_radius", 0.05}, {"glow_strength", 0.5}}}});
  cm::add_quantised(mw, "mean", cm::quantise_images(mean.data(), 1, px, cm::DType::kU16), 1, w, h);
  cm::add_quantised(mw, "eigen", cm::quantise_images(eig.data(), e, px, cm::DType::kU8), e, w, h);
  mw.add_f32("weights", {f, e}, weights);
  mw.add_f32("variance", {e}, var);
  mw.add_i32("graph.offsets", {f + 1}, off);
  mw.add_i32("graph.successors", {3}, succ);
  mw.add_f32("graph.cost", {3}, cost);
  mw.write(std::string(argv[1]) + "/seed.cmodel");
  return 0;
}
