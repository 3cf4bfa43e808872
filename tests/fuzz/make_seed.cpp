// Writes a seed corpus for model_reader_fuzz: one small valid model.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "model/model_file.h"
#include "model/model_writer.h"

int main(int argc, char** argv) {
  if (argc < 2) return 2;
  namespace cm = candela::model;
  const int w = 4, h = 3, e = 2, f = 3;
  const size_t px = w * h;
  std::vector<float> mean(px, 20.0f), eig(e * px), weights(f * e, 1.0f), var{2.0f, 1.0f};
  for (size_t i = 0; i < eig.size(); ++i) eig[i] = std::sin(static_cast<float>(i));
  // Weights that move (a model whose frames are all alike is refused).
  for (size_t i = 0; i < weights.size(); ++i) weights[i] = 1.0f + static_cast<float>(i % 3);
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
  // Issue 15 regression input: frame 2's only way on is a jump costing 1e7 x
  // the median, whose preference rounded to 0 and was divided by (SIGFPE).
  std::vector<float> extreme{1, 1, 1e7f};
  mw.add_f32("graph.cost", {3}, extreme);
  mw.write(std::string(argv[1]) + "/regress-extreme-jump-cost.cmodel");
  mw.add_f32("graph.cost", {3}, cost);
  // The same with a Learning Flames part (an order-2 ARP over 2 + 2 + 1 + 1
  // parameters), so the fuzzer reaches the ARP and shape players too.
  const int np = 2, nw = 2, ne = 1, d = np + nw + 1 + ne, t = 4, lw = 3, lh = 4;
  nlohmann::json info = cm::ModelFile::from_bytes(mw.bytes(), "seed").info();
  info["learning_flames"] = {{"np", np},    {"nw", nw},      {"ne", ne},
                             {"order", 2},  {"width", lw},   {"height", lh},
                             {"frames", t}, {"base_y", 3.0}, {"span", 2.5}};
  mw.set_info(info);
  std::vector<float> lmean(lw * lh, 40.0f), leig(ne * lw * lh, 0.3f), params(t * d),
      a(2 * d * d, 0.0f), dd(d, 0.5f), b(d * d, 0.0f);
  for (size_t i = 0; i < params.size(); ++i) params[i] = 1.0f + static_cast<float>(i % 7);
  for (int i = 0; i < d; ++i) a[i * d + i] = 0.5f, b[i * d + i] = 0.1f;
  cm::add_quantised(mw, "lf.mean", cm::quantise_images(lmean.data(), 1, lw * lh, cm::DType::kU8), 1,
                    lw, lh);
  cm::add_quantised(mw, "lf.eigen", cm::quantise_images(leig.data(), ne, lw * lh, cm::DType::kU8),
                    ne, lw, lh);
  mw.add_f32("lf.params", {t, d}, params);
  mw.add_f32("arp.A", {2, d, d}, a);
  mw.add_f32("arp.d", {d}, dd);
  mw.add_f32("arp.B", {d, d}, b);
  mw.write(std::string(argv[1]) + "/seed-lf.cmodel");
  return 0;
}
