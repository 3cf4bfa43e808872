// GPU cost of the eigen-flame's reconstruction with the built-in fire model
// (299 components, 128x160, 300 frames), on whatever GL the headless display
// gets (llvmpipe on the CI machines): the full sum a model frame costs on its
// first visit (the fire fireplace's late frames while the walk is new), and
// the redraw of a frame from the frame cache (every later visit). Each
// iteration ends with glFinish, so the time is the GPU's.
#include <benchmark/benchmark.h>

#include <memory>

#include "display/display.h"
#include "elements/eigenflame/eigen_renderer.h"
#include "elements/eigenflame/eigenflame.h"
#include "gl/gles.h"
#include "model/flame_model.h"

namespace candela {
namespace {

std::unique_ptr<Display> headless() {
  DisplayOptions o;
  o.kind = "headless";
  o.vsync = false;
  o.width = 64;
  o.height = 64;
  return open_display(o);
}

// One model frame after another, each summed over every component.
void BM_EigenFullSum(benchmark::State& state) {
  const auto display = headless();
  const auto fire = builtin_eigen_model("fire");
  const model::FlameModel& m = *fire->model;
  EigenReconstructor r(image_stack_of(m.mean), image_stack_of(m.eigen), StackLayout::kPacked,
                       m.components());
  int f = 0;
  for (auto _ : state) {
    r.reconstruct(m.weights_of(f));
    glFinish();
    f = (f + 1) % m.frames();
  }
  state.counters["pixels"] = static_cast<double>(m.width()) * m.height();
}
BENCHMARK(BM_EigenFullSum)->Unit(benchmark::kMillisecond);

// The same frames from the frame cache (filled before the timing).
void BM_EigenCachedFrame(benchmark::State& state) {
  const auto display = headless();
  const auto fire = builtin_eigen_model("fire");
  const model::FlameModel& m = *fire->model;
  EigenReconstructor r(image_stack_of(m.mean), image_stack_of(m.eigen), StackLayout::kPacked,
                       m.components());
  const int frames = 30;
  if (!r.enable_cache(m.weights, frames, m.components())) {
    state.SkipWithError("no frame cache on this GL");
    return;
  }
  for (int f = 0; f < frames; ++f) r.cache_frame(f);
  glFinish();
  int f = 0;
  for (auto _ : state) {
    glBindFramebuffer(GL_FRAMEBUFFER, r.framebuffer());
    r.draw_near_frame_at(m.weights_of(f), f, 0, 0);
    glFinish();
    f = (f + 1) % frames;
  }
}
BENCHMARK(BM_EigenCachedFrame)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace candela
