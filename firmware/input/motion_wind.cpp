#include "input/motion_wind.h"

#include <cmath>
#include <cstdlib>

namespace candela {

void downsample_gray(const uint8_t* src, int width, int height, int f, uint8_t* dst) {
  const int w = width / f, h = height / f, n = f * f;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      int sum = 0;
      for (int dy = 0; dy < f; ++dy) {
        const uint8_t* row = src + static_cast<size_t>(y * f + dy) * width + x * f;
        for (int dx = 0; dx < f; ++dx) sum += row[dx];
      }
      dst[static_cast<size_t>(y) * w + x] = static_cast<uint8_t>((sum + n / 2) / n);
    }
}

MotionDetector::MotionDetector(int width, int height, int threshold)
    : width_(width),
      height_(height),
      threshold_(threshold),
      previous_(static_cast<size_t>(width) * height) {}

Motion MotionDetector::feed(const uint8_t* gray) {
  Motion m;
  const size_t n = previous_.size();
  if (has_previous_) {
    uint32_t count = 0;
    uint64_t sum_x = 0;
    for (int y = 0; y < height_; ++y) {
      const uint8_t* a = previous_.data() + static_cast<size_t>(y) * width_;
      const uint8_t* b = gray + static_cast<size_t>(y) * width_;
      for (int x = 0; x < width_; ++x)
        if (std::abs(b[x] - a[x]) > threshold_) {
          ++count;
          sum_x += static_cast<uint64_t>(x);
        }
    }
    m.area = static_cast<float>(count) / static_cast<float>(n);
    if (count)
      m.centroid_x = (static_cast<float>(sum_x) / count + 0.5f) / static_cast<float>(width_);
  }
  std::copy(gray, gray + n, previous_.begin());
  has_previous_ = true;
  return m;
}

CameraWindLogic::CameraWindLogic(const InputSpec& spec, uint16_t source, const WindSpec& wind)
    : source_(source),
      mirror_(spec.mirror),
      sensitivity_(spec.sensitivity),
      strength_(spec.strength < Fixed{} ? wind.gust_speed : spec.strength),
      cooldown_ns_(static_cast<int64_t>(spec.cooldown_ms) * 1'000'000) {}

void CameraWindLogic::frame(const Motion& m, int64_t t_ns, InputEventSink& sink) {
  if (m.area < kMinArea || m.area > kMaxArea) {
    tracked_ = 0;  // a sweep must be seen in consecutive frames
    moving_ = false;
    return;
  }
  // The first frame of a run of motion sees an object half in view (or only
  // where it started): its centroid lags, so the track starts a frame later.
  if (!moving_) {
    moving_ = true;
    return;
  }
  if (tracked_ == kTrack) {
    for (int i = 1; i < kTrack; ++i) track_[i - 1] = track_[i];
    --tracked_;
  }
  track_[tracked_++] = {t_ns, m.centroid_x};
  if (tracked_ < kTrack) return;
  // Least-squares slope of centroid over time, and every step the same way.
  double st = 0, sx = 0;
  for (const auto& s : track_) st += static_cast<double>(s.t_ns - track_[0].t_ns) * 1e-9, sx += s.x;
  st /= kTrack, sx /= kTrack;
  double num = 0, den = 0;
  int rising = 0, falling = 0;
  for (int i = 0; i < kTrack; ++i) {
    const double dt = static_cast<double>(track_[i].t_ns - track_[0].t_ns) * 1e-9 - st;
    num += dt * (track_[i].x - sx);
    den += dt * dt;
    if (i) (track_[i].x > track_[i - 1].x ? rising : falling) += 1;
  }
  if (den <= 0) return;
  double speed = num / den;     // image widths per second, + = toward the image's right
  if (mirror_) speed = -speed;  // facing the room: the image's right is the viewer's left
  last_speed_ = speed;
  if (rising && falling) return;
  if (std::fabs(speed) * sensitivity_ < kMinSpeed || t_ns - last_gust_ns_ < cooldown_ns_) return;
  // One image width per second gives the configured strength; faster, more (up to 3x).
  const double gain = std::min(3.0, std::fabs(speed) * sensitivity_);
  const Fixed s = Fixed::from_double(strength_.to_double() * gain);
  InputEvent e;
  e.wind = {WindEvent::Type::kGust, speed > 0 ? s : -s, {}};
  e.cause_ns = track_[0].t_ns;
  e.source = source_;
  sink.emit(e);
  ++gusts_;
  last_gust_ns_ = t_ns;
  tracked_ = 0;
}

}  // namespace candela
