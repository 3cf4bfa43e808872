// CPU cost of the candle's animation (the paper measured 0.44 ms per candle
// on a Pentium D, drawing included): one CandleRig step, a group of candles
// sharing a wind field with breezes, the wind sample alone, and, for
// comparison, the 8x8 mesh warp done on the CPU (the runtime does it in the
// vertex shader).
#include <benchmark/benchmark.h>

#include <vector>

#include "elements/candle/candle_rig.h"
#include "elements/candle/flame_warp.h"
#include "scene/element.h"
#include "wind/wind_field.h"

namespace candela {
namespace {

WindSpec breezy() {
  WindSpec s;
  s.breeze_interval = Fixed::from_int(3);
  s.breeze_speed = Fixed::from_ratio(3, 2);
  return s;
}

// Steps `count` candles on a grid through calm and breezes; reports time per candle-step.
void BM_CandleStep(benchmark::State& state) {
  const int count = static_cast<int>(state.range(0));
  WindField wind(breezy());
  std::vector<CandleRig> rigs;
  rigs.reserve(count);
  for (int i = 0; i < count; ++i)
    rigs.emplace_back(CandleParams{}, StillLayout{},
                      WindPosition{Fixed::from_ratio(i % 20, 10), Fixed::from_ratio(i / 20, 10)},
                      static_cast<uint64_t>(i + 1));
  StepContext step;
  step.dt = Fixed::from_ratio(1, 60);
  step.wind = &wind;
  for (auto _ : state) {
    wind.update(step);
    for (auto& r : rigs) r.update(step);
    ++step.step;
    benchmark::DoNotOptimize(rigs.back().lines());
  }
  state.SetItemsProcessed(state.iterations() * count);
  state.counters["ns_per_candle"] =
      benchmark::Counter(static_cast<double>(state.iterations() * count),
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_CandleStep)->Arg(1)->Arg(25)->Arg(100)->Arg(400)->Unit(benchmark::kMicrosecond);

void BM_WindSample(benchmark::State& state) {
  WindField wind(breezy());
  StepContext step;
  step.dt = Fixed::from_ratio(1, 60);
  for (int i = 0; i < 200; ++i) wind.update(step);
  wind.push({WindEvent::Type::kGust, Fixed::from_int(2), {}});
  WindPosition p{Fixed::from_ratio(1, 3), Fixed::from_ratio(-1, 5)};
  for (auto _ : state) {
    benchmark::DoNotOptimize(wind.sample(p));
    p.x.raw ^= 1;
  }
}
BENCHMARK(BM_WindSample);

void BM_MeshWarpCpu(benchmark::State& state) {
  const int cells = static_cast<int>(state.range(0));
  CandleRig rig(CandleParams{}, StillLayout{}, {}, 3);
  for (int i = 0; i < 120; ++i) rig.update({Fixed::from_ratio(1, 2), {}}, Fixed::from_ratio(1, 60));
  const auto dest = to_warp_lines(rig.lines());
  auto src = to_warp_lines(source_lines(StillLayout{}));
  src.resize(dest.size());
  const auto verts = mesh_vertices(cells, 0.5);
  for (auto _ : state) benchmark::DoNotOptimize(warp_mesh(verts, src, dest, {}));
}
BENCHMARK(BM_MeshWarpCpu)->Arg(8)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace candela
