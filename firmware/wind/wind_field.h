// The wind every element reads. Sources (a steady wind, gusts from keys,
// sensors or the camera) push WindEvents; elements sample the field at their
// position each fixed step. An element never knows where the wind came from.
#pragma once

#include <cstdint>

#include "core/fixed.h"
#include "display/display.h"
#include "gl/math.h"

namespace candela {

class ParamReader;
struct StepContext;

struct WindSpec {
  Vec3 direction{1, 0, 0};  // where the steady wind blows to (x: right, z: toward viewer)
  Fixed speed;              // steady wind, m/s
  Fixed gust_speed = Fixed::from_int(2);  // a key or button gust's peak, m/s
  Fixed gust_seconds = Fixed::from_ratio(3, 2);
};
WindSpec parse_wind(ParamReader& reader);

// Wind at one place: x = left->right, z = back->front (toward the viewer), m/s.
struct WindSample {
  Fixed x, z;
};

struct WindEvent {
  enum class Type : uint8_t { kGust, kSteady, kBlowOut } type = Type::kGust;
  Fixed x, z;  // direction * strength (m/s)
};

class WindField {
 public:
  explicit WindField(const WindSpec& spec = {});
  void push(const WindEvent& event);
  void on_key(Key key);
  void update(const StepContext& step);
  WindSample sample(Vec3 position) const;

 private:
  WindSpec spec_;
  WindSample steady_;
  WindSample gust_dir_;
  Fixed gust_age_;
  Fixed gust_length_;
  bool gust_active_ = false;
  WindSample current_gust_;
};

}  // namespace candela
