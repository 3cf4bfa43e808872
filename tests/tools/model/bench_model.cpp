// Model-builder benchmarks (not a ctest test). Baselines from the papers
// (i7-2600K, MATLAB/C++): EigenFires PCA of 2197 frames at 410x670 took 45 min
// + 20 min projection; Direct Bridging 65-101 ms, End Growing 104-416 ms per
// transition; Learning Flames ARP learning 30 min.
//   build/tests/tools/model/bench_model
#include <benchmark/benchmark.h>

#include <cstdio>
#include <memory>

#include "ingest.h"
#include "model_build.h"
#include "transitions.h"

namespace ct = candela::tools;

namespace {

const char* const kClips[] = {"candle_breeze_tfg_flameshaken", "candle_schodl_singan",
                              "candle_red_ngasocute", "candle_triplet_oscillating_cpldcpu",
                              "campfire_night_slowmo_implax"};

// The paper's dataset size: 2197 frames of 410x670, resampled from the real clips.
const ct::Dataset& paper_sized_dataset() {
  static std::unique_ptr<ct::Dataset> d = [] {
    std::vector<ct::SourceClip> clips;
    for (const char* c : kClips)
      clips.push_back(ct::read_source(std::string(CANDELA_FLAMES_DIR) + "/" + c));
    ct::IngestOptions o;
    o.width = 410;
    o.height = 670;
    std::fprintf(stderr, "bench_model: ingesting the clips at 410x670...\n");
    ct::Dataset small = ct::ingest(clips, o);
    return std::make_unique<ct::Dataset>(ct::resample_dataset(small, 2197));
  }();
  return *d;
}

const ct::BuiltModel& paper_sized_model() {
  static std::unique_ptr<ct::BuiltModel> m = [] {
    ct::BuildOptions o;
    return std::make_unique<ct::BuiltModel>(ct::build_model(paper_sized_dataset(), o));
  }();
  return *m;
}

void BM_BuildModel_2197x410x670(benchmark::State& state) {
  const ct::Dataset& d = paper_sized_dataset();
  ct::BuildOptions o;
  o.pca.components = static_cast<int>(state.range(0));
  for (auto _ : state) {
    ct::BuiltModel m = ct::build_model(d, o);
    auto bytes = m.writer.bytes();
    benchmark::DoNotOptimize(bytes.data());
    state.counters["E"] = m.pca.components();
    state.counters["holdout_dB"] = m.psnr.back().holdout_db;
    state.counters["model_MB"] = static_cast<double>(bytes.size()) / 1e6;
  }
  state.counters["vs_paper_65min"] =
      benchmark::Counter(65.0 * 60.0, benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_BuildModel_2197x410x670)
    ->Arg(64)
    ->Arg(128)
    ->Iterations(1)
    ->Unit(benchmark::kSecond)
    ->UseRealTime();

void BM_Transition(benchmark::State& state) {
  const ct::BuiltModel& m = paper_sized_model();
  const ct::Dataset& d = paper_sized_dataset();
  ct::WeightSpace s = ct::WeightSpace::from(m.pca.weights, d.clips);
  ct::TransitionOptions o;
  o.theta_min = m.graph.median_step;
  o.steps = state.range(0) == 0 ? 3 : 40;
  // Pairs across the clips, as in the paper's Figures 7-9.
  const std::pair<int, int> pairs[] = {{100, 600}, {700, 1500}, {1300, 300}, {1900, 1000}};
  size_t i = 0, found = 0, frames = 0;
  for (auto _ : state) {
    auto [a, b] = pairs[i++ % 4];
    ct::Transition t =
        state.range(0) == 0 ? ct::direct_bridging(s, a, b, o) : ct::end_growing(s, a, b, o);
    found += t.found;
    frames += t.path.size();
    benchmark::DoNotOptimize(t.path.data());
  }
  state.counters["found_share"] =
      static_cast<double>(found) / static_cast<double>(state.iterations());
  state.counters["path_frames"] =
      static_cast<double>(frames) / static_cast<double>(state.iterations());
  state.SetLabel(state.range(0) == 0 ? "direct bridging N=3 (paper 65-101 ms)"
                                     : "end growing N=40 (paper 104-416 ms)");
}
BENCHMARK(BM_Transition)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

// Learning Flames dynamics alone: EM with condensation (Nc = 200, K = 2) on
// the 26 parameters of the single-plume frames of the paper-sized dataset.
void BM_ArpLearning(benchmark::State& state) {
  const ct::BuiltModel& m = paper_sized_model();
  const ct::Dataset& d = paper_sized_dataset();
  ct::LearningFlamesOptions o;
  o.learn_dynamics = true;
  for (auto _ : state) {
    ct::LearningFlamesModel lf = ct::learn_flames(d, o);
    state.counters["frames"] = static_cast<double>(lf.frames.size());
    state.counters["em_iterations"] = lf.dynamics.iterations;
  }
  state.SetLabel("shape + appearance + ARP; paper: 30 min (ARP)");
  benchmark::DoNotOptimize(m.pca.components());
}
BENCHMARK(BM_ArpLearning)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
