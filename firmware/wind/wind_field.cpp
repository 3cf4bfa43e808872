#include "wind/wind_field.h"

#include "scene/element.h"
#include "scene/params.h"

namespace candela {

WindSpec parse_wind(ParamReader& r) {
  WindSpec s;
  s.direction = r.vec3("direction", s.direction);
  s.speed = r.fixed("speed", 0, 0, 30);
  s.gust_speed = r.fixed("gust_speed", s.gust_speed.to_double(), 0, 30);
  s.gust_seconds = r.fixed("gust_seconds", s.gust_seconds.to_double(), 0.1, 30);
  r.finish();
  return s;
}

WindField::WindField(const WindSpec& spec) : spec_(spec) {
  const Vec3 d = normalize(spec.direction);
  steady_ = {Fixed::from_double(d.x) * spec.speed, Fixed::from_double(d.z) * spec.speed};
}

void WindField::push(const WindEvent& e) {
  switch (e.type) {
    case WindEvent::Type::kSteady:
      steady_ = {e.x, e.z};
      break;
    case WindEvent::Type::kGust:
    case WindEvent::Type::kBlowOut:
      gust_dir_ = {e.x, e.z};
      gust_age_ = Fixed{};
      gust_length_ = spec_.gust_seconds;
      gust_active_ = true;
      break;
  }
}

void WindField::on_key(Key key) {
  const Fixed g = spec_.gust_speed;
  switch (key) {
    case Key::kLeft:
      push({WindEvent::Type::kGust, g, {}});
      break;  // from the left: blows right
    case Key::kRight:
      push({WindEvent::Type::kGust, -g, {}});
      break;
    case Key::kUp:
      push({WindEvent::Type::kGust, {}, g});
      break;
    case Key::kDown:
      push({WindEvent::Type::kGust, {}, -g});
      break;
    case Key::kSpace:
      push({WindEvent::Type::kGust, {}, g});
      break;  // toward the viewer
    case Key::kBlowOut:
      push({WindEvent::Type::kBlowOut, g * 4, {}});
      break;
    default:
      break;
  }
}

void WindField::update(const StepContext& step) {
  if (!gust_active_) {
    current_gust_ = {};
    return;
  }
  gust_age_ += step.dt;
  if (gust_age_ >= gust_length_) {
    gust_active_ = false;
    current_gust_ = {};
    return;
  }
  // A triangle envelope: rises for the first quarter, falls for the rest.
  const Fixed t = gust_age_ / gust_length_;
  const Fixed q = Fixed::from_ratio(1, 4);
  const Fixed env = t < q ? t / q : (Fixed::from_int(1) - t) / (Fixed::from_int(1) - q);
  current_gust_ = {gust_dir_.x * env, gust_dir_.z * env};
}

WindSample WindField::sample(Vec3) const {
  return {steady_.x + current_gust_.x, steady_.z + current_gust_.z};
}

}  // namespace candela
