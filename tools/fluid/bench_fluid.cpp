// Speed of the fire tools: one 128x128 solver step (target < 2 ms), one
// 256x256 texture-synthesis key frame (target < 2 s), and the whole
// default-data recipe (target < 5 min).
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "fire_animation.h"
#include "flame_photo.h"
#include "fluid_solver.h"
#include "texture_synth.h"

namespace candela::fluid {
namespace {

FluidParams bench_params() {
  FluidParams p;  // 128x128, one source, all terms on
  p.sources = {HeatSource{}};
  p.sources[0].y = 0.1;
  p.sources[0].rx = 0.07;
  p.sources[0].ry = 0.1;
  p.sources[0].rate = 40000.0;
  p.buoyancy = 0.08;
  p.vorticity = 0.8;
  return p;
}

void BM_SimulationStep128(benchmark::State& state) {
  FluidSolver s(bench_params());
  for (int k = 0; k < 120; ++k) s.step(1.0 / 60.0);  // a developed flame, not still air
  int iters = 0;
  for (auto _ : state) {
    const StepStats st = s.step(1.0 / 60.0);
    iters += st.pressure.iterations;
  }
  state.counters["cg_iterations"] = benchmark::Counter(iters, benchmark::Counter::kAvgIterations);
}
BENCHMARK(BM_SimulationStep128)->Unit(benchmark::kMillisecond);

void BM_TextureKeyFrame256(benchmark::State& state) {
  FluidSolver s(bench_params());
  for (int k = 0; k < 180; ++k) s.step(1.0 / 60.0);
  FieldFrame f;
  f.temperature = s.temperature();
  f.t_reference = s.max_temperature();
  const std::vector<float> target = temperature_target(f, 2);  // 256x256
  const Exemplar photo = make_exemplar(render_flame_photo(96, 160, 1), ControlChannel::kAuto, 5);
  TextureSynthesizer synth(photo, SynthParams{});
  Pcg32 rng(1);
  for (auto _ : state) {
    RgbImage img = synth.synthesize(target, 256, 256, rng);
    benchmark::DoNotOptimize(img.px.data());
  }
}
BENCHMARK(BM_TextureKeyFrame256)->Unit(benchmark::kMillisecond);

// The recipe as a user runs it (300 frames per clip), into a scratch folder.
void BM_DefaultDataRecipe(benchmark::State& state) {
  const std::string out = std::string(CANDELA_BINARY_DIR) + "/bench-scratch/default-data";
  const std::string cmd = "CANDELA_TOOL='" + std::string(CANDELA_TOOL_EXE) + "' sh '" +
                          std::string(CANDELA_SOURCE_DIR) + "/tools/fluid/make-default-data.sh' '" +
                          out + "' >/dev/null 2>&1";
  for (auto _ : state) {
    std::filesystem::remove_all(out);
    if (std::system(cmd.c_str()) != 0) state.SkipWithError("make-default-data.sh failed");
  }
  std::filesystem::remove_all(out);
}
BENCHMARK(BM_DefaultDataRecipe)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();

}  // namespace
}  // namespace candela::fluid
