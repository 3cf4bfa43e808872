#include "wind/wind_field.h"

#include <cmath>

#include "core/log.h"
#include "embedded_noise_tables.h"
#include "params/params.h"
#include "wind/fixed_math.h"
#include "wind/step_context.h"

namespace candela {

WindSpec parse_wind(ParamReader& r) {
  WindSpec s;
  s.direction = r.vec3("direction", s.direction);
  const double dx = s.direction.x, dz = s.direction.z, len = std::sqrt(dx * dx + dz * dz);
  if (!(len >= 1e-3) || !std::isfinite(len))
    r.fail("direction", "expected a direction with an x or z component, e.g. [1, 0, 0]");
  // Only the direction matters: kept as a unit vector, so [40000, 0, 0] cannot
  // overflow the fixed-point maths the field runs on.
  s.direction = {static_cast<float>(dx / len), 0.0f, static_cast<float>(dz / len)};
  s.speed = r.fixed("speed", 0, 0, 30);
  s.gust_speed = r.fixed("gust_speed", s.gust_speed.to_double(), 0, 30);
  s.gust_seconds = r.fixed("gust_seconds", s.gust_seconds.to_double(), 0.1, 30);
  s.plane_distance = r.fixed("plane_distance", s.plane_distance.to_double(), 0, 100);
  s.travel_speed = r.fixed("travel_speed", s.travel_speed.to_double(), 0.05, 100);
  s.attenuation = r.fixed("attenuation", s.attenuation.to_double(), 0, 100);
  s.blowout_speed = r.fixed("blowout_speed", s.blowout_speed.to_double(), 0, 100);
  s.breeze_interval = r.fixed("breeze_interval", 0, 0, 3600);
  s.breeze_speed = r.fixed("breeze_speed", s.breeze_speed.to_double(), 0, 30);
  s.breeze_seconds = r.fixed("breeze_seconds", s.breeze_seconds.to_double(), 0.2, 60);
  s.breeze_spread = r.fixed("breeze_spread", s.breeze_spread.to_double(), 0, 1);
  s.seed = static_cast<uint64_t>(r.integer("seed", 1, 0, INT64_MAX));
  s.gust_table = r.path("gust_table");
  if (!s.gust_table.empty()) {
    try {
      NoiseTable::load(s.gust_table);  // validated now, so --check reports it
    } catch (const std::exception& e) {
      r.fail("gust_table", std::string("expected a noise table: ") + e.what());
    }
  }
  r.finish();
  return s;
}

namespace {
NoiseTable load_gust_table(const WindSpec& spec) {
  if (!spec.gust_table.empty()) {
    try {
      return NoiseTable::load(spec.gust_table);
    } catch (const std::exception& e) {
      LOG_ERROR("wind: %s; using the built-in gust table", e.what());
    }
  }
  return NoiseTable::parse(noise_tables::find("gust_b24.cnoise"), "<built-in gust_b24.cnoise>");
}
}  // namespace

WindField::WindField(const WindSpec& spec)
    : spec_(spec), gust_table_(load_gust_table(spec)), rng_(spec.seed, 0x77696e64) {
  const Fixed dx = Fixed::from_double(spec.direction.x), dz = Fixed::from_double(spec.direction.z);
  const Fixed len = fixed_hypot(dx, dz);
  dir_x_ = len.raw > 0 ? dx / len : Fixed::from_int(1);
  dir_z_ = len.raw > 0 ? dz / len : Fixed{};
  steady_ = {dir_x_ * spec.speed, dir_z_ * spec.speed};
  history_.fill(steady_);
  inv_travel_speed_ = Fixed::from_int(1) / spec.travel_speed;
}

void WindField::start_gust(Fixed x, Fixed z, Fixed length_seconds) {
  const Fixed peak = fixed_hypot(x, z);
  if (peak.raw <= 0) return;
  // Reuse an idle slot, else replace the oldest gust.
  Gust* slot = &gusts_[0];
  for (auto& g : gusts_) {
    if (!g.active) {
      slot = &g;
      break;
    }
    if (g.start < slot->start) slot = &g;
  }
  slot->dx = x / peak;
  slot->dz = z / peak;
  slot->peak = peak;
  slot->start = now_;
  slot->length_steps = static_cast<int32_t>(steps_in(length_seconds, steps_per_second_));
  if (slot->length_steps < 2) slot->length_steps = 2;
  slot->active = true;
}

void WindField::push(const WindEvent& e) {
  switch (e.type) {
    case WindEvent::Type::kSteady:
      steady_ = {e.x, e.z};
      break;
    case WindEvent::Type::kGust:
    case WindEvent::Type::kBlowOut:
      start_gust(e.x, e.z, spec_.gust_seconds);
      break;
  }
}

void WindField::update(const StepContext& step) {
  if (step.dt.raw > 0) steps_per_second_ = (Fixed::kOne + step.dt.raw / 2) / step.dt.raw;
  if (now_ == 0 && spec_.breeze_interval.raw > 0)
    next_breeze_ =
        static_cast<uint64_t>(steps_in(spec_.breeze_interval * rng_.unit(), steps_per_second_));
  ++now_;
  history_[now_ % kHistorySteps] = steady_;
  for (auto& g : gusts_) {
    // A gust is over once its tail has passed the farthest point it can
    // reach within the delay history.
    if (g.active && now_ - g.start > static_cast<uint64_t>(g.length_steps) +
                                         static_cast<uint64_t>(kHistorySteps))
      g.active = false;
  }
  if (spec_.breeze_interval.raw > 0 && now_ >= next_breeze_) {
    // Direction scattered sideways around the scene's wind direction.
    const Fixed side = (rng_.unit() * 2 - Fixed::from_int(1)) * spec_.breeze_spread;
    Fixed bx = dir_x_ - dir_z_ * side, bz = dir_z_ + dir_x_ * side;
    const Fixed len = fixed_hypot(bx, bz);
    const Fixed strength =
        spec_.breeze_speed * (Fixed::from_ratio(3, 5) + rng_.unit() * Fixed::from_ratio(2, 5));
    bx = bx / len * strength;
    bz = bz / len * strength;
    start_gust(
        bx, bz,
        spec_.breeze_seconds * (Fixed::from_ratio(7, 10) + rng_.unit() * Fixed::from_ratio(3, 5)));
    const Fixed wait = spec_.breeze_interval * (Fixed::from_ratio(1, 2) + rng_.unit());
    next_breeze_ = now_ + static_cast<uint64_t>(steps_in(wait, steps_per_second_)) + 1;
  }
}

Fixed WindField::distance_from_plane(WindPosition p, Fixed dx, Fixed dz) const {
  const Fixed d = spec_.plane_distance + p.x * dx + p.z * dz;
  return d.raw < 0 ? Fixed{} : d;
}

Fixed WindField::attenuation_at(const WindSpec& spec, Fixed distance) {
  return Fixed::from_int(1) / (Fixed::from_int(1) + spec.attenuation * distance);
}

WindTravel WindField::travel(const WindSpec& spec, WindPosition from, WindPosition to, Fixed x,
                             Fixed z) {
  WindTravel t;
  const Fixed peak = fixed_hypot(x, z);
  if (peak.raw <= 0) return t;
  t.distance = (to.x - from.x) * (x / peak) + (to.z - from.z) * (z / peak);
  if (t.distance.raw < 0) return t;
  t.reached = true;
  // As sample() does within one screen: d / travel_speed, 1 / (1 + a d).
  t.delay = t.distance * (Fixed::from_int(1) / spec.travel_speed);
  t.gain = attenuation_at(spec, spec.plane_distance + t.distance) /
           attenuation_at(spec, spec.plane_distance);
  return t;
}

Fixed WindField::delay_seconds(WindPosition p, Fixed dx, Fixed dz) const {
  return distance_from_plane(p, dx, dz) * inv_travel_speed_;
}

int WindField::active_gusts() const {
  int n = 0;
  for (const auto& g : gusts_) n += g.active;
  return n;
}

WindSample WindField::sample(WindPosition p) const {
  // Steady wind: what S emitted `delay` steps ago.
  const Fixed d0 = distance_from_plane(p, dir_x_, dir_z_);
  int64_t delay = steps_in(d0 * inv_travel_speed_, steps_per_second_);
  if (delay > kHistorySteps - 1) delay = kHistorySteps - 1;
  const uint64_t at = now_ > static_cast<uint64_t>(delay) ? now_ - delay : 0;
  const WindSample& s = history_[at % kHistorySteps];
  const Fixed a0 = attenuate(d0);
  WindSample w{s.x * a0, s.z * a0};
  for (const auto& g : gusts_) {
    if (!g.active) continue;
    const Fixed d = distance_from_plane(p, g.dx, g.dz);
    // Age of the gust here, in steps (Q16): it left S at g.start.
    const int64_t age_q16 = (static_cast<int64_t>(now_ - g.start) << 16) -
                            static_cast<int64_t>((d * inv_travel_speed_).raw) * steps_per_second_;
    if (age_q16 < 0 || age_q16 >= (static_cast<int64_t>(g.length_steps) << 16)) continue;
    const auto pos = static_cast<uint32_t>(age_q16 * gust_table_.length() / g.length_steps);
    const Fixed strength = g.peak * gust_table_.at(pos) * attenuate(d);
    w.x += g.dx * strength;
    w.z += g.dz * strength;
  }
  return w;
}

}  // namespace candela
