// Host-runnable tests of the input pieces that need no hardware: the queue,
// debounce, the anemometer's rate maths, what each sensor does to the wind,
// [[input]] validation, and camera motion -> gust direction.
#include <gtest/gtest.h>

#include <thread>
#include <vector>

#include "core/error.h"
#include "input/motion_wind.h"
#include "input/sensor_logic.h"
#include "input/spsc_queue.h"
#include "scene/scene_file.h"

namespace candela {
namespace {

constexpr int64_t kMs = 1'000'000;

struct Collect : InputEventSink {
  std::vector<InputEvent> events;
  void emit(const InputEvent& e) override { events.push_back(e); }
};

TEST(SpscQueue, KeepsOrderAndDropsWhenFull) {
  SpscQueue<int, 4> q;
  for (int i = 0; i < 4; ++i) EXPECT_TRUE(q.push(i));
  EXPECT_FALSE(q.push(99));
  EXPECT_EQ(q.dropped(), 1u);
  int v = -1;
  for (int i = 0; i < 4; ++i) {
    ASSERT_TRUE(q.pop(v));
    EXPECT_EQ(v, i);
  }
  EXPECT_FALSE(q.pop(v));
}

TEST(SpscQueue, TwoThreadsSeeEveryItemInOrder) {
  SpscQueue<uint32_t, 64> q;
  constexpr uint32_t kN = 200000;
  std::thread producer([&] {
    for (uint32_t i = 0; i < kN;)
      if (q.push(i)) ++i;
  });
  uint32_t expect = 0, v = 0;
  while (expect < kN)
    if (q.pop(v)) {
      ASSERT_EQ(v, expect);
      ++expect;
    }
  producer.join();
}

TEST(Debouncer, SwallowsABurstShorterThanTheDebounceTime) {
  Debouncer d(20 * kMs, false);
  // 5 edges within 8 ms, ending low again: contact noise.
  for (int i = 0; i < 6; ++i) d.edge(i % 2 == 0, (100 + i * 2) * kMs);
  bool level = false;
  int64_t at = 0;
  EXPECT_FALSE(d.settle(200 * kMs, level, at));
  EXPECT_FALSE(d.level());
}

TEST(Debouncer, AcceptsABouncyPressOnceSettled) {
  Debouncer d(20 * kMs, false);
  d.edge(true, 100 * kMs);
  d.edge(false, 101 * kMs);
  d.edge(true, 103 * kMs);
  bool level = false;
  int64_t at = 0;
  EXPECT_FALSE(d.settle(110 * kMs, level, at));  // still bouncing
  EXPECT_EQ(d.deadline(), 123 * kMs);
  ASSERT_TRUE(d.settle(123 * kMs, level, at));
  EXPECT_TRUE(level);
  EXPECT_EQ(at, 100 * kMs);  // the press began at the first edge
}

InputSpec gpio_spec(InputSpec::Kind kind) {
  InputSpec s;
  s.kind = kind;
  s.name = "t";
  s.chip = "x";
  s.line_offset = 0;
  s.debounce_ms = 10;
  return s;
}

TEST(SensorLogic, ButtonGustBlowsAwayFromItsSide) {
  InputSpec s = gpio_spec(InputSpec::Kind::kButton);
  s.dir_x = Fixed::from_int(-1);  // side = right: blows left
  WindSpec w;
  w.gust_speed = Fixed::from_int(3);
  SensorLogic logic(s, 7, w);
  logic.start(false, 0);
  Collect c;
  logic.edge(true, 50 * kMs, c);
  logic.edge(false, 52 * kMs, c);  // bounce
  logic.edge(true, 53 * kMs, c);
  EXPECT_TRUE(c.events.empty());
  logic.service(63 * kMs, c);
  ASSERT_EQ(c.events.size(), 1u);
  EXPECT_EQ(c.events[0].wind.type, WindEvent::Type::kGust);
  EXPECT_EQ(c.events[0].wind.x, Fixed::from_int(-3));
  EXPECT_EQ(c.events[0].wind.z, Fixed{});
  EXPECT_EQ(c.events[0].source, 7);
  EXPECT_EQ(c.events[0].cause_ns, 50 * kMs);
  // Release: no second gust.
  logic.edge(false, 300 * kMs, c);
  logic.service(400 * kMs, c);
  EXPECT_EQ(c.events.size(), 1u);
  EXPECT_EQ(logic.activations(), 1u);
}

TEST(SensorLogic, BlowSensorGivesABlowOutEvent) {
  InputSpec s = gpio_spec(InputSpec::Kind::kBlow);
  s.dir_z = Fixed::from_int(-1);
  WindSpec w;  // gust_speed 2 -> blow 8
  SensorLogic logic(s, 0, w);
  logic.start(false, 0);
  Collect c;
  logic.edge(true, 10 * kMs, c);
  logic.service(30 * kMs, c);
  ASSERT_EQ(c.events.size(), 1u);
  EXPECT_EQ(c.events[0].wind.type, WindEvent::Type::kBlowOut);
  EXPECT_EQ(c.events[0].wind.z, Fixed::from_int(-8));
}

TEST(SensorLogic, PresenceAddsADraughtWhilePresent) {
  InputSpec s = gpio_spec(InputSpec::Kind::kPresence);
  s.dir_z = Fixed::from_int(-1);
  s.strength = Fixed::from_ratio(3, 10);
  WindSpec w;
  w.direction = {1, 0, 0};
  w.speed = Fixed::from_ratio(1, 2);
  SensorLogic logic(s, 0, w);
  logic.start(false, 0);
  Collect c;
  logic.edge(true, 10 * kMs, c);
  logic.service(30 * kMs, c);
  ASSERT_EQ(c.events.size(), 1u);
  EXPECT_EQ(c.events[0].wind.type, WindEvent::Type::kSteady);
  EXPECT_EQ(c.events[0].wind.x, Fixed::from_ratio(1, 2));  // the scene's own wind stays
  EXPECT_EQ(c.events[0].wind.z, -Fixed::from_ratio(3, 10));
  logic.edge(false, 1000 * kMs, c);
  logic.service(1020 * kMs, c);
  ASSERT_EQ(c.events.size(), 2u);
  EXPECT_EQ(c.events[1].wind.z, Fixed{});
  EXPECT_EQ(c.events[1].wind.x, Fixed::from_ratio(1, 2));
}

TEST(PulseRateMeter, MeasuresRateIndependentOfWindowPhase) {
  PulseRateMeter m(2000 * kMs);
  // 12.5 Hz with +-3 ms jitter.
  const int jitter[] = {3, -2, 0, 1, -3, 2, -1, 0};
  int64_t t = 0;
  for (int i = 0; i < 60; ++i) {
    t = i * 80 * kMs + jitter[i % 8] * kMs;
    m.pulse(t);
  }
  EXPECT_NEAR(m.rate_hz(t + 10 * kMs), 12.5, 12.5 * 0.01);
  EXPECT_NEAR(m.rate_hz(t + 70 * kMs), 12.5, 12.5 * 0.01);
  // The wind stops: the estimate falls, then reaches zero once the window is empty.
  EXPECT_LT(m.rate_hz(t + 500 * kMs), 2.5);
  EXPECT_EQ(m.rate_hz(t + 2100 * kMs), 0);
}

TEST(SensorLogic, AnemometerSpeedFollowsPulseRate) {
  InputSpec s = gpio_spec(InputSpec::Kind::kAnemometer);
  s.debounce_ms = 2;
  s.dir_x = Fixed::from_int(1);
  s.calibration = 0.667;
  s.window_s = 2;
  SensorLogic logic(s, 0, WindSpec{});
  logic.start(false, 0);
  Collect c;
  // 5 Hz reed pulses, 20 ms closed, each with a 1 ms bounce at closing.
  int64_t t = 0;
  for (int i = 0; i < 20; ++i) {
    t = 1000 * kMs + i * 200 * kMs;
    logic.edge(true, t, c);
    logic.edge(false, t + kMs / 2, c);
    logic.edge(true, t + kMs, c);
    logic.edge(false, t + 20 * kMs, c);
    logic.service(t + 25 * kMs, c);
  }
  ASSERT_FALSE(c.events.empty());
  const InputEvent& last = c.events.back();
  EXPECT_EQ(last.wind.type, WindEvent::Type::kSteady);
  EXPECT_NEAR(last.wind.x.to_double(), 5 * 0.667, 5 * 0.667 * 0.02);
  EXPECT_EQ(logic.activations(), 20u);
  // Pulses stop: the wind decays to nothing.
  for (int64_t now = t + 100 * kMs; now < t + 3000 * kMs; now += 100 * kMs) logic.service(now, c);
  EXPECT_EQ(c.events.back().wind.x, Fixed{});
}

TEST(InputConfig, ParsesEveryKind) {
  const SceneDesc d = load_scene_text(R"(
[wind]
gust_speed = 2.5
[[input]]
kind = "button"
name = "left button"
chip = "vboard-gpio"
line_name = "sim3"
bias = "pull-down"
side = "right"
[[input]]
kind = "anemometer"
chip = "/dev/gpiochip0"
line = 4
calibration = 1.25
window_s = 3
active_low = true
[[input]]
kind = "camera"
device = "/dev/video0"
mirror = false
)",
                                      "t.toml");
  ASSERT_EQ(d.inputs.size(), 3u);
  EXPECT_EQ(d.inputs[0].name, "left button");
  EXPECT_EQ(d.inputs[0].line_name, "sim3");
  EXPECT_EQ(d.inputs[0].bias, InputSpec::Bias::kPullDown);
  EXPECT_EQ(d.inputs[0].dir_x, Fixed::from_int(-1));
  EXPECT_EQ(d.inputs[0].debounce_ms, 20);
  EXPECT_EQ(d.inputs[1].line_offset, 4);
  EXPECT_TRUE(d.inputs[1].active_low);
  EXPECT_DOUBLE_EQ(d.inputs[1].calibration, 1.25);
  EXPECT_EQ(d.inputs[1].debounce_ms, 2);
  EXPECT_EQ(d.inputs[2].kind, InputSpec::Kind::kCamera);
  EXPECT_FALSE(d.inputs[2].mirror);
}

TEST(InputConfig, LibcameraCameraIds) {
  // Pi camera ids are device-tree paths: they start with "/" but are no /dev node.
  for (const char* id : {"platform/vimc.0 Sensor B", "/base/soc/i2c0mux/i2c@1/imx708@1a", "auto"}) {
    const SceneDesc d = load_scene_text(
        std::string("[[input]]\nkind = \"camera\"\nbackend = \"libcamera\"\ndevice = \"") + id +
            "\"\n",
        "t.toml");
    ASSERT_EQ(d.inputs.size(), 1u);
    EXPECT_EQ(d.inputs[0].backend, "libcamera");
    EXPECT_EQ(d.inputs[0].device, id);
  }
}

void expect_error(const char* toml, const std::string& key, const std::string& says) {
  try {
    load_scene_text(toml, "s.toml");
    ADD_FAILURE() << "accepted: " << toml;
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.file(), "s.toml");
    EXPECT_EQ(e.key(), key) << e.what();
    EXPECT_NE(std::string(e.what()).find(says), std::string::npos) << e.what();
  }
}

TEST(InputConfig, ErrorsNameTheKey) {
  expect_error("[[input]]\nkind='button'\nchip='c'\n", "input[0].line", "exactly one of line");
  expect_error("[[input]]\nkind='button'\nchip='c'\nline=1\nline_name='a'\n", "input[0].line",
               "exactly one");
  expect_error("[[input]]\nkind='button'\nline=1\n", "input[0].chip", "missing");
  expect_error("[[input]]\nkind='fan'\n", "input[0].kind", "button");
  expect_error("[[input]]\nkind='button'\nchip='c'\nline=1\ndebounce=5\n", "input[0].debounce", "");
  expect_error("[[input]]\nkind='anemometer'\nchip='c'\nline=1\ncalibration=-1\n",
               "input[0].calibration", "");
  expect_error("[[input]]\nkind='camera'\ndevice='video0'\n", "input[0].device", "/dev/video0");
  expect_error("[[input]]\nkind='camera'\nbackend='libcamera'\ndevice='/dev/video0'\n",
               "input[0].device", "libcamera camera id");
  expect_error("[[input]]\nkind='camera'\nbackend='v4l2'\ndevice='platform/vimc.0 Sensor B'\n",
               "input[0].device", "for backend \"v4l2\"");
  expect_error("[[input]]\nkind='camera'\nbackend='gphoto'\n", "input[0].backend", "libcamera");
  expect_error("input = 3\n", "input", "array of tables");
}

// --- camera motion -----------------------------------------------------------

constexpr int kW = 160, kH = 120;

// A bright textured "hand" (a block) on a dark, slightly noisy background.
std::vector<uint8_t> scene_with_block(int block_x, uint32_t noise_seed) {
  std::vector<uint8_t> img(kW * kH);
  uint32_t r = noise_seed * 2654435761u + 1;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      r = r * 1664525u + 1013904223u;
      int v = 40 + static_cast<int>((r >> 24) % 9) - 4;  // +-4 sensor noise
      if (x >= block_x && x < block_x + 30 && y >= 30 && y < 100) v = 200 + ((x + y) % 5) * 8;
      img[y * kW + x] = static_cast<uint8_t>(v);
    }
  return img;
}

std::vector<InputEvent> wave(int from_x, int step, int frames, bool mirror) {
  InputSpec s;
  s.kind = InputSpec::Kind::kCamera;
  s.mirror = mirror;
  MotionDetector det(kW, kH);
  CameraWindLogic logic(s, 3, WindSpec{});
  Collect c;
  for (int i = 0; i < frames; ++i) {
    const auto img = scene_with_block(from_x + i * step, static_cast<uint32_t>(i));
    logic.frame(det.feed(img.data()), int64_t{i} * (1'000'000'000 / 15), c);
  }
  return c.events;
}

TEST(CameraMotion, HandMovingRightBlowsRight) {
  const auto ev = wave(-20, 8, 20, false);  // 8 px/frame at 15 fps: 0.75 image widths/s
  ASSERT_GE(ev.size(), 1u);
  EXPECT_EQ(ev[0].wind.type, WindEvent::Type::kGust);
  EXPECT_GT(ev[0].wind.x, Fixed{});
  EXPECT_EQ(ev[0].source, 3);
}

TEST(CameraMotion, HandMovingLeftBlowsLeft) {
  const auto ev = wave(150, -8, 20, false);
  ASSERT_GE(ev.size(), 1u);
  for (const auto& e : ev) EXPECT_LT(e.wind.x, Fixed{});
}

TEST(CameraMotion, MirroredCameraSwapsSides) {
  const auto ev = wave(-20, 8, 20, true);
  ASSERT_GE(ev.size(), 1u);
  EXPECT_LT(ev[0].wind.x, Fixed{});
}

TEST(CameraMotion, FasterSweepBlowsHarder) {
  const auto slow = wave(-20, 6, 28, false), fast = wave(-20, 14, 12, false);
  ASSERT_FALSE(slow.empty());
  ASSERT_FALSE(fast.empty());
  EXPECT_GT(fast[0].wind.x.raw, slow[0].wind.x.raw * 3 / 2);
}

TEST(CameraMotion, StillFramesGiveNoGust) { EXPECT_TRUE(wave(60, 0, 40, false).empty()); }

TEST(CameraMotion, WholeFrameBrightnessChangeGivesNoGust) {
  InputSpec s;
  s.kind = InputSpec::Kind::kCamera;
  MotionDetector det(kW, kH);
  CameraWindLogic logic(s, 0, WindSpec{});
  Collect c;
  for (int i = 0; i < 20; ++i) {
    auto img = scene_with_block(60, 1);
    for (auto& p : img)
      p = static_cast<uint8_t>(std::min(255, p + (i % 2) * 40));  // lights flicker
    logic.frame(det.feed(img.data()), i * 66 * kMs, c);
  }
  EXPECT_TRUE(c.events.empty());
}

TEST(CameraMotion, DownsampleAveragesBlocks) {
  const uint8_t src[4 * 2] = {0, 2, 10, 20, 4, 6, 30, 40};
  uint8_t dst[2];
  downsample_gray(src, 4, 2, 2, dst);
  EXPECT_EQ(dst[0], 3);
  EXPECT_EQ(dst[1], 25);
}

}  // namespace
}  // namespace candela
