// Several screens, one room (input/room.h): how far, how late and how strong
// a gust reaches another display, and what a room message must be.
#include "input/room.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

#include "app/config_file.h"
#include "core/error.h"
#include "input/input_hub.h"
#include "scene/element.h"
#include "support/allocation_counter.h"
#include "wind/wind_field.h"

namespace candela {
namespace {

WindPosition at(double x, double z) { return {Fixed::from_double(x), Fixed::from_double(z)}; }

// The scene defaults: S 1 m upwind, 1.5 m/s, 1 / (1 + 0.3 d).
TEST(RoomTravel, DelayAndAttenuationFollowPlaneS) {
  const WindSpec spec;
  const Fixed two = Fixed::from_int(2), zero;
  WindTravel t = WindField::travel(spec, at(0, 0), at(1, 0), two, zero);
  ASSERT_TRUE(t.reached);
  EXPECT_NEAR(t.distance.to_double(), 1.0, 1e-4);
  EXPECT_NEAR(t.delay.to_double(), 1.0 / 1.5, 1e-4);
  EXPECT_NEAR(t.gain.to_double(), (1 + 0.3 * 1) / (1 + 0.3 * 2), 1e-4);
  t = WindField::travel(spec, at(0, 0), at(2, 0), two, zero);
  ASSERT_TRUE(t.reached);
  EXPECT_NEAR(t.delay.to_double(), 2.0 / 1.5, 1e-4);
  EXPECT_NEAR(t.gain.to_double(), 1.3 / 1.9, 1e-4);
  // Only the distance along the gust counts: a display beside the origin
  // (across the gust) gets it at once, at full strength.
  t = WindField::travel(spec, at(0, 0), at(0, 3), two, zero);
  ASSERT_TRUE(t.reached);
  EXPECT_NEAR(t.delay.to_double(), 0.0, 1e-4);
  EXPECT_NEAR(t.gain.to_double(), 1.0, 1e-4);
  // Diagonal: the projection on the gust's direction.
  t = WindField::travel(spec, at(1, 1), at(2, 2), two, two);
  ASSERT_TRUE(t.reached);
  EXPECT_NEAR(t.distance.to_double(), std::sqrt(2.0), 1e-3);
  // Upwind of the origin, or no gust at all: not reached.
  EXPECT_FALSE(WindField::travel(spec, at(1, 0), at(0, 0), two, zero).reached);
  EXPECT_FALSE(WindField::travel(spec, at(0, 0), at(1, 0), zero, zero).reached);
  // The scene's own travel speed and attenuation are used.
  WindSpec slow;
  slow.travel_speed = Fixed::from_ratio(1, 2);
  slow.attenuation = Fixed{};
  t = WindField::travel(slow, at(0, 0), at(1, 0), two, zero);
  EXPECT_NEAR(t.delay.to_double(), 2.0, 1e-4);
  EXPECT_NEAR(t.gain.to_double(), 1.0, 1e-4);
}

// One room is one wind field: a second display's field, given the gust
// `delay` later and weakened by `gain`, blows at its origin what a single
// field blows at that display's place.
TEST(RoomTravel, TwoFieldsMatchOneField) {
  const WindSpec spec;
  WindField one(spec), here(spec);
  StepContext step;
  step.dt = Fixed::from_ratio(1, 60);
  const WindTravel t = WindField::travel(spec, at(0, 0), at(1, 0), Fixed::from_int(2), Fixed{});
  const auto delay_steps = static_cast<int>(std::lround(t.delay.to_double() * 60));
  EXPECT_EQ(delay_steps, 40);
  one.push({WindEvent::Type::kGust, Fixed::from_int(2), Fixed{}});
  double peak_one = 0, peak_here = 0, max_diff = 0;
  for (int i = 0; i < 400; ++i) {
    if (i == delay_steps) here.push({WindEvent::Type::kGust, Fixed::from_int(2) * t.gain, Fixed{}});
    one.update(step);
    here.update(step);
    const double a = one.sample(at(1, 0)).x.to_double();
    const double b = here.sample(at(0, 0)).x.to_double();
    peak_one = std::max(peak_one, a);
    peak_here = std::max(peak_here, b);
    max_diff = std::max(max_diff, std::fabs(a - b));
  }
  EXPECT_GT(peak_one, 0.5);
  EXPECT_LT(max_diff, 0.02 * peak_one) << peak_one << " " << peak_here;
}

TEST(RoomMessage, RoundTrip) {
  RoomGust g;
  g.origin = "candela-shop_a";
  g.seq = 7;
  g.t_ns = 1764770000123456789;
  g.type = WindEvent::Type::kBlowOut;
  g.x = -2.5;
  g.z = 0.25;
  g.px = 1.5;
  g.pz = -3;
  const std::string json = room_gust_json(g);
  EXPECT_LE(json.size(), RoomGust::kMaxMessage);
  std::string error;
  const auto back = parse_room_gust(json, &error);
  ASSERT_TRUE(back) << error;
  EXPECT_EQ(back->origin, g.origin);
  EXPECT_EQ(back->seq, 7u);
  EXPECT_EQ(back->t_ns, g.t_ns);  // exact: a 64-bit integer, not a double
  EXPECT_EQ(back->type, WindEvent::Type::kBlowOut);
  EXPECT_DOUBLE_EQ(back->x, -2.5);
  EXPECT_DOUBLE_EQ(back->z, 0.25);
  EXPECT_DOUBLE_EQ(back->px, 1.5);
  EXPECT_DOUBLE_EQ(back->pz, -3);
  // The receiver's arrival from the message alone.
  const WindTravel t = room_travel(WindSpec{}, *back, 0.5, -3);
  ASSERT_TRUE(t.reached);
  EXPECT_NEAR(t.distance.to_double(), 1.0 * 2.5 / std::hypot(2.5, 0.25), 1e-3);
}

TEST(RoomMessage, BadMessagesAreRefusedWithTheReason) {
  const std::string good =
      R"({"v":1,"origin":"a","seq":1,"t_ns":5,"type":"gust","x":1,"z":0,"position":[0,0]})";
  std::string error;
  ASSERT_TRUE(parse_room_gust(good, &error)) << error;
  struct Case {
    std::string payload, reason;
  };
  const Case cases[] = {
      {"", "expected JSON"},
      {"{\"v\":1,", "expected JSON"},
      {"[1,2]", "a JSON object"},
      {std::string(600, ' '), "at most 512 bytes"},
      {R"({"v":2,"origin":"a","seq":1,"t_ns":5,"type":"gust","x":1,"z":0,"position":[0,0]})",
       "v: expected 1"},
      {R"({"v":1,"seq":1,"t_ns":5,"type":"gust","x":1,"z":0,"position":[0,0]})", "origin:"},
      {R"({"v":1,"origin":"a b","seq":1,"t_ns":5,"type":"gust","x":1,"z":0,"position":[0,0]})",
       "origin: expected 1..64 printable"},
      {R"({"v":1,"origin":"a","seq":-1,"t_ns":5,"type":"gust","x":1,"z":0,"position":[0,0]})",
       "seq:"},
      {R"({"v":1,"origin":"a","seq":1,"t_ns":"5","type":"gust","x":1,"z":0,"position":[0,0]})",
       "t_ns:"},
      {R"({"v":1,"origin":"a","seq":1,"t_ns":0,"type":"gust","x":1,"z":0,"position":[0,0]})",
       "t_ns:"},
      {R"({"v":1,"origin":"a","seq":1,"t_ns":5,"type":"steady","x":1,"z":0,"position":[0,0]})",
       "type:"},
      {R"({"v":1,"origin":"a","seq":1,"t_ns":5,"type":"gust","x":1e9,"z":0,"position":[0,0]})",
       "x: expected a number"},
      {R"({"v":1,"origin":"a","seq":1,"t_ns":5,"type":"gust","x":1,"z":null,"position":[0,0]})",
       "z: expected a number"},
      {R"({"v":1,"origin":"a","seq":1,"t_ns":5,"type":"gust","x":1,"z":0,"position":[0]})",
       "position:"},
      {R"({"v":1,"origin":"a","seq":1,"t_ns":5,"type":"gust","x":1,"z":0,"position":[0,500]})",
       "position:"},
  };
  for (const Case& c : cases) {
    error.clear();
    EXPECT_FALSE(parse_room_gust(c.payload, &error)) << c.payload;
    EXPECT_NE(error.find(c.reason), std::string::npos) << c.payload << " -> " << error;
  }
}

// The frame loop's side: local gusts go out, received ones wait for their
// time, nothing received goes out again, nothing allocated.
TEST(RoomHub, GustsOutAndInWithoutAllocating) {
  InputHub hub({}, WindSpec{});
  WindField wind;
  InputHub::RoomOut out;
  // No room: nothing for the room.
  ASSERT_EQ(hub.answer("gust left 2"), "ok");
  hub.drain(wind);
  EXPECT_EQ(wind.active_gusts(), 1);
  EXPECT_FALSE(hub.take_room_gust(out));

  hub.enable_room(1, 0);
  ASSERT_EQ(hub.answer("gust left 2"), "ok");
  ASSERT_EQ(hub.answer("wind 0.5 0"), "ok");  // steady wind: not a gust, not sent
  InputHub::RoomIn later, due;
  later.wind = {WindEvent::Type::kGust, Fixed::from_int(1), Fixed{}};
  later.due_mono_ns = monotonic_ns() + 60'000'000'000;
  due = later;
  due.due_mono_ns = monotonic_ns() - 1;
  due.origin_ns = 11;
  due.due_ns = 22;
  ASSERT_TRUE(hub.give_room_gust(later));
  ASSERT_TRUE(hub.give_room_gust(due));
  const int64_t before = realtime_ns();
  test::start_counting_allocations();
  hub.drain(wind);
  hub.drain(wind);
  const long allocations = test::stop_counting_allocations();
  if (test::allocations_counted()) {
    EXPECT_EQ(allocations, 0);
  }
  EXPECT_EQ(wind.active_gusts(), 3);  // the first, the local one, the due one
  ASSERT_TRUE(hub.take_room_gust(out));
  EXPECT_EQ(out.wind.type, WindEvent::Type::kGust);
  EXPECT_NEAR(out.wind.x.to_double(), 2.0, 1e-3);
  EXPECT_GE(out.t_ns, before - 1'000'000'000);
  EXPECT_LE(out.t_ns, realtime_ns());
  EXPECT_FALSE(hub.take_room_gust(out));  // the received one is not passed on
  const std::string state = hub.state_json();
  EXPECT_NE(state.find(R"("applied":1,"waiting":1)"), std::string::npos) << state;
  EXPECT_NE(state.find(R"("origin_ns":11)"), std::string::npos) << state;
  EXPECT_NE(state.find(R"("due_ns":22)"), std::string::npos) << state;
}

std::string write_config(const std::string& body) {
  char name[] = "/tmp/candela-room-XXXXXX";
  const int fd = mkstemp(name);
  EXPECT_GE(fd, 0);
  close(fd);
  std::ofstream(name) << body;
  return name;
}

TEST(RoomConfig, ReadAndValidated) {
  const std::string mqtt = "[mqtt]\nhost = \"127.0.0.1\"\n";
  std::string path = write_config(mqtt + "[room]\nposition = [1.5, -2]\ntopic = \"shop/room\"\n");
  const KioskConfig c = load_config_file(path);
  std::remove(path.c_str());
  EXPECT_TRUE(c.mqtt.room.enabled);
  EXPECT_DOUBLE_EQ(c.mqtt.room.x, 1.5);
  EXPECT_DOUBLE_EQ(c.mqtt.room.z, -2);
  EXPECT_EQ(c.mqtt.room.topic, "shop/room");
  path = write_config(mqtt);
  EXPECT_FALSE(load_config_file(path).mqtt.room.enabled);  // no [room]: no room
  std::remove(path.c_str());
  struct Case {
    std::string body, key, expected;
  };
  const Case cases[] = {
      {"[room]\nposition = [0, 0]\n", "room.position", "without [mqtt]"},
      {mqtt + "[room]\ntopic = \"r\"\n", "room.position", "missing"},
      {mqtt + "[room]\nposition = [1]\n", "room.position", "[x, z]"},
      {mqtt + "[room]\nposition = [1, 2, 3]\n", "room.position", "at most 2"},
      {mqtt + "[room]\nposition = [1, 200]\n", "room.position", "[-100, 100]"},
      {mqtt + "[room]\nposition = \"here\"\n", "room.position", "array"},
      {mqtt + "[room]\nposition = [0, 0]\ntopic = \"a/#\"\n", "room.topic", "no wildcards"},
      {mqtt + "[room]\nposition = [0, 0]\nspeed = 1\n", "room.speed", ""},
  };
  for (const Case& k : cases) {
    path = write_config(k.body);
    try {
      load_config_file(path);
      ADD_FAILURE() << "accepted: " << k.body;
    } catch (const ConfigError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(path), std::string::npos) << what;
      EXPECT_NE(what.find(k.key), std::string::npos) << what;
      EXPECT_NE(what.find(k.expected), std::string::npos) << what;
    }
    std::remove(path.c_str());
  }
}

}  // namespace
}  // namespace candela
