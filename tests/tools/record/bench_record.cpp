// What the live preview costs the recorder: handing it one frame (a copy into
// the triple buffer, an index swap and a wake-up), with the preview thread
// drawing at the same time (headless, Mesa llvmpipe) or switched off.
#include <benchmark/benchmark.h>

#include <vector>

#include "preview.h"

namespace {

using candela::record::PreviewOptions;
using candela::record::RecordPreview;

void push_frames(benchmark::State& state, const char* mode, int channels) {
  PreviewOptions o;
  o.mode = mode;
  o.width = 320;
  o.height = 240;
  RecordPreview preview(o, nullptr);
  preview.start(640, 480, channels);
  preview.wait_until_open();
  std::vector<uint8_t> frame(640 * 480 * static_cast<size_t>(channels), 90);
  uint32_t seq = 0;
  for (auto _ : state) {
    preview.push(frame.data(), seq++);
    benchmark::ClobberMemory();
  }
  preview.stop();
  state.counters["shown"] = static_cast<double>(preview.shown());
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations()) *
                          static_cast<int64_t>(frame.size()));
}

void BM_PushGray640x480_PreviewOff(benchmark::State& s) { push_frames(s, "off", 1); }
void BM_PushGray640x480_Headless(benchmark::State& s) { push_frames(s, "headless", 1); }
void BM_PushRgb640x480_Headless(benchmark::State& s) { push_frames(s, "headless", 3); }
BENCHMARK(BM_PushGray640x480_PreviewOff);
BENCHMARK(BM_PushGray640x480_Headless);
BENCHMARK(BM_PushRgb640x480_Headless);

}  // namespace
