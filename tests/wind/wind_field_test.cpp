// WindField: plane S, delay by distance / travel speed, attenuation, gust
// shape, breezes; and the integer trig it relies on.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "input/input_hub.h"
#include "wind/step_context.h"
#include "wind/fixed_math.h"
#include "wind/wind_field.h"

namespace candela {
namespace {

StepContext step_at(uint64_t i) {
  StepContext s;
  s.step = i;
  s.dt = Fixed::from_ratio(1, 60);
  s.time = Fixed::from_ratio(static_cast<int64_t>(i), 60);
  return s;
}

double magnitude(WindSample w) { return std::hypot(w.x.to_double(), w.z.to_double()); }

TEST(FixedMath, SinCosSqrtMatchTheRealFunctions) {
  double worst = 0;
  for (int i = -4000; i <= 4000; ++i) {
    const double a = i * 0.0025;  // -10 .. 10 rad
    const Fixed f = Fixed::from_double(a);
    worst = std::max(worst, std::abs(fixed_sin(f).to_double() - std::sin(f.to_double())));
    worst = std::max(worst, std::abs(fixed_cos(f).to_double() - std::cos(f.to_double())));
  }
  EXPECT_LT(worst, 3.0 / 65536);
  for (double v : {0.0, 1e-4, 0.25, 2.0, 100.0, 30000.0})
    EXPECT_NEAR(fixed_sqrt(Fixed::from_double(v)).to_double(),
                std::sqrt(Fixed::from_double(v).to_double()), 1.0 / 65536);
  EXPECT_NEAR(fixed_hypot(Fixed::from_int(3), Fixed::from_int(-4)).to_double(), 5.0, 1e-4);
}

// First step at which the wind at p exceeds `level`, over `steps` steps.
int first_above(WindField& w, WindPosition p, double level, int steps, double* peak = nullptr) {
  int first = -1;
  for (int i = 0; i < steps; ++i) {
    w.update(step_at(i));
    const double m = magnitude(w.sample(p));
    if (peak) *peak = std::max(*peak, m);
    if (first < 0 && m > level) first = i;
  }
  return first;
}

TEST(WindField, GustReachesAFartherPlaceLaterByDistanceOverSpeed) {
  WindSpec spec;
  spec.travel_speed = Fixed::from_ratio(3, 2);
  spec.gust_seconds = Fixed::from_int(2);
  const WindPosition near{Fixed::from_double(-0.5), {}}, far{Fixed::from_double(1.0), {}};
  int t_near, t_far;
  {
    WindField w(spec);
    w.push({WindEvent::Type::kGust, Fixed::from_int(2), {}});  // blows toward +x
    t_near = first_above(w, near, 0.3, 600);
  }
  {
    WindField w(spec);
    w.push({WindEvent::Type::kGust, Fixed::from_int(2), {}});
    // Same point of the gust's rise: the threshold weakened as the gust is.
    t_far = first_above(w, far, 0.3 * (1 + 0.3 * 0.5) / (1 + 0.3 * 2.0), 600);
  }
  ASSERT_GE(t_near, 0);
  ASSERT_GE(t_far, 0);
  // 1.5 m more at 1.5 m/s: one second, 60 steps.
  EXPECT_NEAR(t_far - t_near, 60, 2);
  // The same from the field's own account of the delay.
  WindField w(spec);
  const Fixed one = Fixed::from_int(1);
  EXPECT_NEAR((w.delay_seconds(far, one, {}) - w.delay_seconds(near, one, {})).to_double(), 1.0,
              1e-3);
}

TEST(WindField, GustStartsAndEndsCalmAndFadesWithDistance) {
  WindSpec spec;
  spec.gust_seconds = Fixed::from_int(2);
  const WindPosition at{{}, {}};
  WindField w(spec);
  w.push({WindEvent::Type::kGust, {}, -Fixed::from_int(2)});  // away from the viewer
  std::vector<double> m;
  double peak_z = 0;
  for (int i = 0; i < 400; ++i) {
    w.update(step_at(i));
    const WindSample s = w.sample(at);
    m.push_back(magnitude(s));
    peak_z = std::min(peak_z, s.z.to_double());
    EXPECT_EQ(s.x.raw, 0);
  }
  // Before it arrives (1 m from S at 1.5 m/s: 40 steps) it is calm.
  for (int i = 0; i < 38; ++i) EXPECT_EQ(m[i], 0.0) << i;
  // It rises from (nearly) nothing: the gust table starts at its minimum.
  int arrive = 0;
  while (m[arrive] == 0.0) ++arrive;
  EXPECT_LT(m[arrive], 0.1);
  EXPECT_LT(m[arrive + 120 - 2], 0.15);  // and ends near calm after 2 s
  EXPECT_EQ(m[arrive + 125], 0.0);
  // Peak: gust speed weakened by 1 / (1 + 0.3 * 1 m).
  EXPECT_NEAR(-peak_z, 2.0 / 1.3, 0.05);
}

TEST(WindField, SteadyWindChangesTravelFromThePlane) {
  WindSpec spec;
  spec.attenuation = Fixed{};
  WindField w(spec);
  const WindPosition near{{}, {}}, far{Fixed::from_int(3), {}};
  for (int i = 0; i < 10; ++i) w.update(step_at(i));
  EXPECT_EQ(w.sample(near).x.raw, 0);
  w.push({WindEvent::Type::kSteady, Fixed::from_int(1), {}});
  int t_near = -1, t_far = -1;
  for (int i = 10; i < 400; ++i) {
    w.update(step_at(i));
    if (t_near < 0 && w.sample(near).x.raw > 0) t_near = i;
    if (t_far < 0 && w.sample(far).x.raw > 0) t_far = i;
  }
  EXPECT_NEAR(t_far - t_near, 120, 1);  // 3 m at 1.5 m/s
  EXPECT_EQ(w.sample(far).x, Fixed::from_int(1));
}

TEST(WindField, BreezesComeOccasionallyAndAreSeeded) {
  WindSpec spec;
  spec.breeze_interval = Fixed::from_int(5);
  spec.seed = 9;
  auto run = [&](WindSpec s) {
    WindField w(s);
    std::vector<int32_t> xs;
    int windy = 0;
    for (int i = 0; i < 60 * 60; ++i) {
      w.update(step_at(i));
      const WindSample m = w.sample(WindPosition{});
      xs.push_back(m.x.raw);
      windy += magnitude(m) > 0.1;
    }
    return std::make_pair(xs, windy);
  };
  const auto a = run(spec), b = run(spec);
  EXPECT_EQ(a.first, b.first);
  // A minute with a breeze every ~5 s of ~4 s: windy a good part of the time, not always.
  EXPECT_GT(a.second, 60 * 60 / 5);
  EXPECT_LT(a.second, 60 * 60 * 95 / 100);
  spec.seed = 10;
  EXPECT_NE(run(spec).first, a.first);
}

TEST(WindField, KeysBlowFromTheirSide) {
  WindField w;
  InputHub keys({}, w.spec());  // keys reach the wind as every input does
  keys.on_key(Key::kLeft);
  keys.on_key(Key::kSpace);
  keys.drain(w);
  double max_x = 0, max_z = 0;
  for (int i = 0; i < 300; ++i) {
    w.update(step_at(i));
    const WindSample s = w.sample(WindPosition{});
    max_x = std::max(max_x, s.x.to_double());
    max_z = std::max(max_z, s.z.to_double());
  }
  EXPECT_GT(max_x, 1.0);
  EXPECT_GT(max_z, 1.0);
}

}  // namespace
}  // namespace candela
