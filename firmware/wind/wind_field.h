// The wind every element reads. Sources (a steady wind; gusts from keys,
// sensors, the camera or the control socket, all through input/InputHub; the
// scene's occasional breezes) push WindEvents; elements sample the field at
// their position each fixed step. An element never knows where the wind came
// from.
//
// As in the candle paper, wind starts at a plane S perpendicular to the
// ground whose normal is the wind's direction; it reaches a point at distance
// d from S after d / travel_speed seconds, weakened by 1 / (1 + attenuation d).
// Gust strength follows a gust noise table (minimum first), so a gust begins
// and ends calm. All state is fixed-point and preallocated.
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include "core/fixed.h"
#include "core/random.h"
#include "gl/math.h"
#include "model/noise_table.h"

namespace candela {

class ParamReader;
struct StepContext;

struct WindSpec {
  Vec3 direction{1, 0, 0};  // where the steady wind blows to (x: right, z: toward viewer)
  Fixed speed;              // steady wind, m/s
  Fixed gust_speed = Fixed::from_int(2);  // a key or button gust's peak, m/s
  Fixed gust_seconds = Fixed::from_ratio(3, 2);
  // Plane S and how wind travels from it.
  Fixed plane_distance = Fixed::from_int(1);     // S lies this far upwind of the origin, m
  Fixed travel_speed = Fixed::from_ratio(3, 2);  // m/s
  Fixed attenuation = Fixed::from_ratio(3, 10);  // 1/m
  Fixed blowout_speed = Fixed::from_int(8);      // the `o` key's gust peak, m/s
  // Occasional breezes along `direction` (0 = none): mean seconds between them.
  Fixed breeze_interval;
  Fixed breeze_speed = Fixed::from_ratio(6, 5);  // peak, m/s
  Fixed breeze_seconds = Fixed::from_int(4);
  Fixed breeze_spread = Fixed::from_ratio(1, 2);  // sideways scatter of a breeze's direction, 0..1
  uint64_t seed = 1;
  std::string gust_table;  // a user noise table for gust shapes (empty: built-in)
};
// Reads the scene's [wind] table; paths are resolved against the scene file.
WindSpec parse_wind(ParamReader& reader);

// Wind at one place: x = left->right, z = back->front (toward the viewer), m/s.
struct WindSample {
  Fixed x, z;
};

// A position on the ground plane, fixed-point (elements convert once).
struct WindPosition {
  Fixed x, z;
  static WindPosition from(Vec3 p) { return {Fixed::from_double(p.x), Fixed::from_double(p.z)}; }
};

// How a gust that left a display's plane S travels to another display of the
// same room (issue 18, input/room.h): the candle paper's plane S, with the
// room as the scene. `distance` is how far downwind of the origin the other
// display stands (along the gust); it is reached after distance /
// travel_speed, weakened by the field's 1 / (1 + attenuation d) taken from
// plane S: attenuate(plane_distance + distance) / attenuate(plane_distance),
// so each display's own candles then add their own part as in one screen.
// A display upwind of the origin (distance < 0) is not reached.
struct WindTravel {
  bool reached = false;
  Fixed distance;  // m, along the gust
  Fixed delay;     // s
  Fixed gain;      // 0..1, applied to the gust's strength
};

struct WindEvent {
  enum class Type : uint8_t { kGust, kSteady, kBlowOut } type = Type::kGust;
  Fixed x, z;  // direction * strength (m/s)
};

class WindField {
 public:
  static constexpr int kMaxGusts = 8;
  static constexpr int kHistorySteps = 1024;  // longest steady-wind delay kept

  explicit WindField(const WindSpec& spec = {});
  void push(const WindEvent& event);
  void update(const StepContext& step);
  WindSample sample(Vec3 position) const { return sample(WindPosition::from(position)); }
  WindSample sample(WindPosition position) const;

  const WindSpec& spec() const { return spec_; }
  // Seconds a change at S takes to reach `position` for wind blowing along
  // the unit vector (dx, dz).
  Fixed delay_seconds(WindPosition position, Fixed dx, Fixed dz) const;
  int active_gusts() const;
  // A gust (x, z: direction * strength) from a display at `from` to one at
  // `to`, both in metres on the room's ground plane (WindTravel above).
  static WindTravel travel(const WindSpec& spec, WindPosition from, WindPosition to, Fixed x,
                           Fixed z);
  uint64_t steps() const { return now_; }

 private:
  struct Gust {
    Fixed dx, dz;  // unit direction
    Fixed peak;    // m/s
    uint64_t start = 0;
    int32_t length_steps = 0;
    bool active = false;
  };
  void start_gust(Fixed x, Fixed z, Fixed length_seconds);
  Fixed distance_from_plane(WindPosition p, Fixed dx, Fixed dz) const;
  Fixed attenuate(Fixed distance) const { return attenuation_at(spec_, distance); }
  static Fixed attenuation_at(const WindSpec& spec, Fixed distance);

  WindSpec spec_;
  NoiseTable gust_table_;
  Fixed dir_x_, dir_z_;  // unit steady/breeze direction
  WindSample steady_;
  std::array<WindSample, kHistorySteps> history_{};
  std::array<Gust, kMaxGusts> gusts_{};
  uint64_t now_ = 0;  // steps seen
  int32_t steps_per_second_ = 60;
  Fixed inv_travel_speed_;
  Pcg32 rng_;
  uint64_t next_breeze_ = 0;
};

}  // namespace candela
