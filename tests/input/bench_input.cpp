// The camera input's cost per frame: YUYV -> gray, downsample, differencing,
// the gust logic. The camera budget is < 5% of one core at 15 fps, i.e.
// < 3.3 ms per frame; the counter "core_percent_at_15fps" says where it is.
#include <benchmark/benchmark.h>
#include <linux/videodev2.h>

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
