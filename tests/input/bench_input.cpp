// The camera input's cost per frame: YUYV -> gray, downsample, differencing,
// the gust logic. The camera budget is < 5% of one core at 15 fps, i.e.
// < 3.3 ms per frame; the counter "core_percent_at_15fps" says where it is.
#include <benchmark/benchmark.h>
#include <linux/videodev2.h>

#include <algorithm>
#include <vector>

#include "input/motion_wind.h"
#include "input/v4l2_capture.h"

namespace candela {
namespace {

struct NullSink : InputEventSink {
  void emit(const InputEvent&) override {}
};

void camera_frame(benchmark::State& state) {
  const int w = static_cast<int>(state.range(0)), h = static_cast<int>(state.range(1));
  V4l2Format f;
  f.fourcc = V4L2_PIX_FMT_YUYV;
  f.width = w;
  f.height = h;
  f.bytesperline = 2 * w;
  f.sizeimage = static_cast<size_t>(2 * w) * h;
  // Two frames with a block in different places, so there is motion to find.
  std::vector<std::vector<uint8_t>> frames(2, std::vector<uint8_t>(f.sizeimage, 60));
  for (int k = 0; k < 2; ++k)
    for (int y = h / 4; y < 3 * h / 4; ++y)
      for (int x = w / 4 + k * w / 16; x < w / 2 + k * w / 16; ++x)
        frames[k][(y * w + x) * 2] = 200;
  const int factor = std::max(1, std::min(w / 160, h / 120));
  std::vector<uint8_t> gray(static_cast<size_t>(w) * h),
      small(static_cast<size_t>(w / factor) * (h / factor));
  MotionDetector det(w / factor, h / factor);
  InputSpec spec;
  spec.kind = InputSpec::Kind::kCamera;
  CameraWindLogic logic(spec, 0, WindSpec{});
  NullSink sink;
  int64_t t = 0;
  size_t i = 0;
  for (auto _ : state) {
    frame_to_gray(f, frames[i & 1].data(), f.sizeimage, gray.data());
    const uint8_t* img = gray.data();
    if (factor > 1) {
      downsample_gray(gray.data(), w, h, factor, small.data());
      img = small.data();
    }
    logic.frame(det.feed(img), t += 66'666'667, sink);
    ++i;
  }
  state.counters["core_percent_at_15fps"] =
      benchmark::Counter(1.0 / (15.0 * 100.0), benchmark::Counter::kIsIterationInvariantRate |
                                                   benchmark::Counter::kInvert);
}
BENCHMARK(camera_frame)
    ->Args({160, 120})
    ->Args({320, 240})
    ->Args({640, 480})
    ->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace candela

// candela-record's per-frame write cost: a 640x480 gray frame to an atomic PNG
// (encode + write + rename) into $TMPDIR. Its rate per writer thread bounds
// the recorder's sustained frame rate without drops.
#include <unistd.h>

#include <cstdlib>
#include <string>

#include "core/image.h"

namespace candela {
namespace {

void record_png_write(benchmark::State& state) {
  const int w = static_cast<int>(state.range(0)), h = static_cast<int>(state.range(1));
  std::vector<uint8_t> px(static_cast<size_t>(w) * h);
  uint32_t r = 12345;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {  // a soft glow with sensor noise: like a flame on black
      r = r * 1664525u + 1013904223u;
      const int dx = x - w / 2, dy = y - h / 2;
      const int glow = std::max(0, 220 - (dx * dx + dy * dy * 4) / (w / 4));
      px[static_cast<size_t>(y) * w + x] =
          static_cast<uint8_t>(std::min(255, glow + static_cast<int>(r >> 29)));
    }
  const char* tmp = std::getenv("TMPDIR");
  const std::string path =
      std::string(tmp ? tmp : "/tmp") + "/candela-bench-" + std::to_string(getpid()) + ".png";
  for (auto _ : state) write_png(path, w, h, 1, px.data());
  unlink(path.c_str());
  state.counters["frames_per_s_per_writer"] =
      benchmark::Counter(1, benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(record_png_write)->Args({320, 180})->Args({640, 480})->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace candela
