#include "input/sensor_logic.h"

#include <cmath>
#include <ctime>

#include "gl/math.h"

namespace candela {

int64_t monotonic_ns() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

void Debouncer::edge(bool level, int64_t t_ns) {
  if (!has_pending_) {
    has_pending_ = true;
    burst_start_ns_ = t_ns;
  }
  pending_ = level;
  last_edge_ns_ = t_ns;
}

bool Debouncer::settle(int64_t now_ns, bool& level, int64_t& burst_start_ns) {
  if (!has_pending_ || now_ns < last_edge_ns_ + debounce_ns_) return false;
  has_pending_ = false;
  if (pending_ == stable_) return false;  // the burst ended where it began: swallowed
  stable_ = pending_;
  level = stable_;
  burst_start_ns = burst_start_ns_;
  return true;
}

void PulseRateMeter::pulse(int64_t t_ns) {
  times_[next_] = t_ns;
  next_ = (next_ + 1) % kMaxPulses;
  if (count_ < kMaxPulses) ++count_;
}

double PulseRateMeter::rate_hz(int64_t now_ns) const {
  size_t n = 0;
  int64_t first = 0, last = 0;
  for (size_t i = 0; i < count_; ++i) {
    const int64_t t = times_[(next_ + kMaxPulses - 1 - i) % kMaxPulses];  // newest first
    if (t <= now_ns - window_ns_) break;
    if (n == 0) last = t;
    first = t;
    ++n;
  }
  if (n < 2 || last <= first) return 0;
  double rate = static_cast<double>(n - 1) * 1e9 / static_cast<double>(last - first);
  // No pulse for clearly longer than the usual interval: the wind has dropped
  // at least that far (the next pulse cannot come sooner than now).
  const double since = static_cast<double>(now_ns - last);
  if (since * rate > 1.5) rate = std::min(rate, 1e9 / since);
  return rate;
}

SensorLogic::SensorLogic(const InputSpec& spec, uint16_t source, const WindSpec& wind)
    : kind_(spec.kind),
      source_(source),
      dir_x_(spec.dir_x),
      dir_z_(spec.dir_z),
      calibration_(spec.calibration),
      debouncer_(static_cast<int64_t>(spec.debounce_ms) * 1'000'000),
      meter_(static_cast<int64_t>(spec.window_s * 1e9)) {
  strength_ = spec.strength;
  if (strength_ < Fixed{})
    strength_ = kind_ == InputSpec::Kind::kBlow ? wind.gust_speed * 4 : wind.gust_speed;
  const Vec3 d = normalize(wind.direction);
  base_x_ = Fixed::from_double(d.x) * wind.speed;
  base_z_ = Fixed::from_double(d.z) * wind.speed;
}

void SensorLogic::start(bool level, int64_t now_ns) {
  debouncer_.reset(level);
  meter_.clear();
  present_ = false;
  (void)now_ns;
}

void SensorLogic::emit(WindEvent::Type type, Fixed x, Fixed z, int64_t t_ns, InputEventSink& sink) {
  InputEvent e;
  e.wind.type = type;
  e.wind.x = x;
  e.wind.z = z;
  e.cause_ns = t_ns;
  e.source = source_;
  sink.emit(e);
}

void SensorLogic::on_level(bool active, int64_t t_ns, InputEventSink& sink) {
  if (active) ++activations_;
  switch (kind_) {
    case InputSpec::Kind::kButton:
      if (active) emit(WindEvent::Type::kGust, dir_x_ * strength_, dir_z_ * strength_, t_ns, sink);
      break;
    case InputSpec::Kind::kBlow:
      if (active)
        emit(WindEvent::Type::kBlowOut, dir_x_ * strength_, dir_z_ * strength_, t_ns, sink);
      break;
    case InputSpec::Kind::kPresence:
      present_ = active;
      if (active)
        emit(WindEvent::Type::kSteady, base_x_ + dir_x_ * strength_, base_z_ + dir_z_ * strength_,
             t_ns, sink);
      else
        emit(WindEvent::Type::kSteady, base_x_, base_z_, t_ns, sink);
      break;
    case InputSpec::Kind::kAnemometer:
      if (active) meter_.pulse(t_ns);
      break;
    case InputSpec::Kind::kCamera:
      break;
  }
}

void SensorLogic::edge(bool active, int64_t t_ns, InputEventSink& sink) {
  bool level = false;
  int64_t at = 0;
  if (debouncer_.settle(t_ns, level, at)) on_level(level, at, sink);
  debouncer_.edge(active, t_ns);
}

int64_t SensorLogic::service(int64_t now_ns, InputEventSink& sink) {
  bool level = false;
  int64_t at = 0;
  if (debouncer_.settle(now_ns, level, at)) on_level(level, at, sink);
  int64_t next = debouncer_.deadline();
  if (kind_ == InputSpec::Kind::kAnemometer) {
    const double speed = meter_.rate_hz(now_ns) * calibration_;
    if (std::fabs(speed - speed_) > std::max(0.01 * speed_, 0.005)) {
      speed_ = speed;
      const Fixed s = Fixed::from_double(speed);
      emit(WindEvent::Type::kSteady, dir_x_ * s, dir_z_ * s, now_ns, sink);
    }
    // While the cups turn, look again soon so a stopping wind decays.
    if (speed_ > 0) {
      const int64_t tick = now_ns + 100'000'000;
      next = next < 0 ? tick : std::min(next, tick);
    }
  }
  return next;
}

void SensorLogic::lost(int64_t now_ns, InputEventSink& sink) {
  if ((kind_ == InputSpec::Kind::kPresence && present_) ||
      (kind_ == InputSpec::Kind::kAnemometer && speed_ > 0))
    emit(WindEvent::Type::kSteady, base_x_, base_z_, now_ns, sink);
  present_ = false;
  speed_ = 0;
  meter_.clear();
}

}  // namespace candela
