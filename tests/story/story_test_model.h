// A small two-clip model for the story tests, built in memory: clips "T1" and
// "T2" are loops (circles of 100 frames, one unit a step) far apart in weight
// space, and clip "middle" is a dense line of frames between them (half a
// step apart), the in-between frames a transition can use. A hard cut from
// T1 to T2 jumps ~30 ordinary steps; the transitions walk the middle.
#pragma once

#include <cmath>
#include <numbers>
#include <vector>

#include "model/flame_model.h"
#include "model/model_writer.h"

namespace candela::test {

inline constexpr int kLoopFrames = 100, kMiddleFrames = 60, kComponents = 8;

inline model::FlameModel two_clip_model() {
  const int w = 8, h = 8, e = kComponents;
  const int f = 2 * kLoopFrames + kMiddleFrames;
  const double r = kLoopFrames / (2 * std::numbers::pi);  // circumference: one unit per frame
  const double gap = 2 * r + 0.5 * (kMiddleFrames + 1);   // centre to centre
  std::vector<float> weights(static_cast<size_t>(f) * e);
  auto set = [&](int frame, double x, double y) {
    float* p = weights.data() + static_cast<size_t>(frame) * e;
    p[0] = static_cast<float>(x);
    p[1] = static_cast<float>(y);
    for (int k = 2; k < e; ++k) p[k] = static_cast<float>(0.02 * std::sin(0.7 * frame + k));
  };
  // T1: frames 0..99 around (0, 0), starting and ending on its right side, (r, 0).
  for (int t = 0; t < kLoopFrames; ++t) {
    const double a = 2 * std::numbers::pi * t / kLoopFrames;
    set(t, r * std::cos(a), r * std::sin(a));
  }
  // middle: frames 100..159 from (r, 0) to (gap - r, 0), half a unit apart.
  for (int t = 0; t < kMiddleFrames; ++t) set(kLoopFrames + t, r + 0.5 * (t + 1), 0);
  // T2: frames 160..259 around (gap, 0), starting and ending on its left side.
  for (int t = 0; t < kLoopFrames; ++t) {
    const double a = std::numbers::pi + 2 * std::numbers::pi * t / kLoopFrames;
    set(kLoopFrames + kMiddleFrames + t, gap + r * std::cos(a), r * std::sin(a));
  }
  // Motion graph: each clip plays on; the loops close on themselves.
  std::vector<int32_t> offsets{0}, succ;
  std::vector<float> cost;
  const int t2 = kLoopFrames + kMiddleFrames;
  for (int i = 0; i < f; ++i) {
    int next = i + 1;
    if (i == kLoopFrames - 1) next = 0;
    if (i == t2 - 1) next = t2;
    if (i == f - 1) next = t2;
    succ.push_back(next);
    cost.push_back(1);
    offsets.push_back(static_cast<int32_t>(succ.size()));
  }
  const size_t px = static_cast<size_t>(w) * h;
  std::vector<float> mean(px, 60.0f), eig(static_cast<size_t>(e) * px), var(e, 1.0f);
  for (int k = 0; k < e; ++k)
    for (size_t p = 0; p < px; ++p)
      eig[k * px + p] = static_cast<float>(std::sin(0.37 * static_cast<double>(p) * (k + 1)));
  auto clip = [](const char* name, int first, int count) {
    return nlohmann::json{{"name", name},   {"source", name}, {"first", first},
                          {"count", count}, {"fps", 30.0},    {"labels", nlohmann::json::array()}};
  };
  model::ModelWriter mw;
  mw.set_info(
      {{"kind", "eigenfires"},
       {"width", w},
       {"height", h},
       {"components", e},
       {"frames", f},
       {"total_variance", 100.0},
       {"graph", {{"theta_min", 0.5}}},
       {"clips",
        {clip("T1", 0, kLoopFrames), clip("middle", kLoopFrames, kMiddleFrames),
         clip("T2", t2, kLoopFrames)}},
       {"colour",
        {{"hue", 30.0}, {"saturation", 0.8}, {"glow_radius", 0.05}, {"glow_strength", 0.0}}},
       {"provenance", {{"tool", "story test"}}}});
  model::add_quantised(mw, "mean", model::quantise_images(mean.data(), 1, px, model::DType::kU16),
                       1, w, h);
  model::add_quantised(mw, "eigen", model::quantise_images(eig.data(), e, px, model::DType::kU8), e,
                       w, h);
  mw.add_f32("weights", {f, e}, weights);
  mw.add_f32("variance", {e}, var);
  mw.add_i32("graph.offsets", {f + 1}, offsets);
  mw.add_i32("graph.successors", {static_cast<int64_t>(succ.size())}, succ);
  mw.add_f32("graph.cost", {static_cast<int64_t>(cost.size())}, cost);
  return model::FlameModel::from(model::ModelFile::from_bytes(mw.bytes(), "<two-clip model>"));
}

}  // namespace candela::test
