// The kiosk's [schedule] (app/schedule.h): validation with file/key errors,
// what it shows at any local time (on/off, fades, night, scenes, what comes
// next), and the Kiosk driving the screen from a fake clock through the same
// path as `screen off`.
#include "app/schedule.h"

#include <gtest/gtest.h>
#include <time.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <thread>

#include "app/config_file.h"
#include "app/kiosk.h"
#include "core/clock.h"
#include "core/error.h"
#include "display/cec_switch.h"
#include "input/input_hub.h"

namespace candela {
namespace {

namespace fs = std::filesystem;

class TempDir {
 public:
  TempDir() {
    std::string t = (fs::temp_directory_path() / "candela-sched-XXXXXX").string();
    path_ = mkdtemp(t.data()) ? t : "";
  }
  ~TempDir() { fs::remove_all(path_); }
  std::string write(const std::string& name, const std::string& text) const {
    const std::string p = path_ + "/" + name;
    std::ofstream(p) << text;
    return p;
  }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

Schedule parse(const std::string& body) {
  TempDir d;
  return load_config_file(d.write("candela.toml", "[schedule]\n" + body)).schedule;
}

// The ConfigError text of a config with this [schedule], or "" if it loads.
std::string error_of(const std::string& body) {
  try {
    parse(body);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

LocalTime at(int weekday, int h, int m, int s = 0) { return {weekday, h * 3600 + m * 60 + s}; }
constexpr int kMon = 0, kTue = 1, kFri = 4, kSat = 5, kSun = 6;

const char* const kWeek =
    "mon-fri = \"07:00-08:30, 17:00-23:30\"\n"
    "sat-sun = \"09:00-01:00\"\n"
    "fade_in = 4\n"
    "fade_out = 10\n"
    "night = \"22:00-06:30\"\n"
    "night_level = 0.4\n"
    "[schedule.scenes]\n"
    "\"17:00-21:00\" = \"eigen-candle\"\n"
    "\"21:00-23:30\" = \"eigen-fireplace\"\n";

TEST(Schedule, OnAndOffTimesPerWeekday) {
  const Schedule s = parse(kWeek);
  ASSERT_TRUE(s.present);
  EXPECT_TRUE(s.has_days);
  EXPECT_FALSE(evaluate_schedule(s, at(kMon, 6, 59, 59)).on);
  EXPECT_TRUE(evaluate_schedule(s, at(kMon, 7, 0)).on);
  EXPECT_TRUE(evaluate_schedule(s, at(kMon, 8, 29, 59)).on);
  EXPECT_FALSE(evaluate_schedule(s, at(kMon, 8, 30)).on);
  EXPECT_TRUE(evaluate_schedule(s, at(kFri, 23, 29)).on);
  EXPECT_FALSE(evaluate_schedule(s, at(kFri, 23, 30)).on);
  EXPECT_FALSE(evaluate_schedule(s, at(kSat, 8, 59)).on);
  // Saturday's 09:00-01:00 runs past midnight into Sunday, Sunday's into Monday.
  EXPECT_TRUE(evaluate_schedule(s, at(kSun, 0, 30)).on);
  EXPECT_FALSE(evaluate_schedule(s, at(kSun, 1, 0)).on);
  EXPECT_TRUE(evaluate_schedule(s, at(kMon, 0, 59)).on);
  EXPECT_FALSE(evaluate_schedule(s, at(kMon, 1, 0)).on);
}

TEST(Schedule, WhatComesNext) {
  const Schedule s = parse(kWeek);
  ScheduleNow n = evaluate_schedule(s, at(kMon, 6, 0));
  EXPECT_FALSE(n.on);
  ASSERT_TRUE(n.has_next);
  EXPECT_TRUE(n.next_on);
  EXPECT_EQ(n.next_in_s, 3600);
  n = evaluate_schedule(s, at(kMon, 8, 0, 15));
  EXPECT_FALSE(n.next_on);
  EXPECT_EQ(n.next_in_s, 30 * 60 - 15);
  // Friday night off until Saturday 09:00.
  n = evaluate_schedule(s, at(kFri, 23, 30));
  EXPECT_EQ(n.next_in_s, (24 - 23) * 3600 - 30 * 60 + 9 * 3600);
  EXPECT_EQ(describe_schedule(s, at(kMon, 6, 0), "default"),
            "now mon 06:00: screen off, level 0.00, scene default; next: on at mon 07:00 (in "
            "1h 0m)");
  EXPECT_EQ(describe_schedule(s, at(kTue, 18, 0), "default"),
            "now tue 18:00: screen on, level 1.00, scene eigen-candle (17:00-21:00); next: off at "
            "tue 23:30 (in 5h 30m)");
  EXPECT_EQ(describe_schedule(s, at(kFri, 23, 45), "default"),
            "now fri 23:45: screen off, level 0.00, scene default; next: on at sat 09:00 (in "
            "9h 15m)");
}

TEST(Schedule, FadesAndNightDimming) {
  const Schedule s = parse(kWeek);
  EXPECT_DOUBLE_EQ(evaluate_schedule(s, at(kMon, 7, 0, 0)).level, 0.0);  // fading in
  EXPECT_DOUBLE_EQ(evaluate_schedule(s, at(kMon, 7, 0, 1)).level, 0.25);
  EXPECT_DOUBLE_EQ(evaluate_schedule(s, at(kMon, 7, 0, 4)).level, 1.0);
  EXPECT_DOUBLE_EQ(evaluate_schedule(s, at(kMon, 8, 29, 55)).level, 0.5);  // fading out
  EXPECT_DOUBLE_EQ(evaluate_schedule(s, at(kMon, 8, 29, 50)).level, 1.0);
  EXPECT_DOUBLE_EQ(evaluate_schedule(s, at(kMon, 12, 0)).level, 0.0);         // off
  EXPECT_NEAR(evaluate_schedule(s, at(kMon, 22, 30)).level, 0.4, 1e-12);      // night
  EXPECT_NEAR(evaluate_schedule(s, at(kMon, 23, 29, 55)).level, 0.2, 1e-12);  // night, fading out
  EXPECT_NEAR(evaluate_schedule(s, at(kSun, 0, 30)).level, 0.4, 1e-12);
}

// Quieter at night, and the sound fades in and out with the picture.
TEST(Schedule, NightVolumeFadesWithThePicture) {
  const Schedule s = parse(std::string(kWeek).insert(0, "night_volume = 0.3\n"));
  EXPECT_DOUBLE_EQ(evaluate_schedule(s, at(kMon, 7, 0, 1)).volume, 0.25);       // fading in
  EXPECT_DOUBLE_EQ(evaluate_schedule(s, at(kMon, 7, 30)).volume, 1.0);          // day: full
  EXPECT_DOUBLE_EQ(evaluate_schedule(s, at(kMon, 12, 0)).volume, 0.0);          // off: silent
  EXPECT_NEAR(evaluate_schedule(s, at(kMon, 22, 30)).volume, 0.3, 1e-12);       // night
  EXPECT_NEAR(evaluate_schedule(s, at(kMon, 22, 30)).level, 0.4, 1e-12);        // its own level
  EXPECT_NEAR(evaluate_schedule(s, at(kMon, 23, 29, 55)).volume, 0.15, 1e-12);  // fading out
  EXPECT_EQ(describe_schedule(s, at(kMon, 22, 30), "default"),
            "now mon 22:30: screen on, level 0.40, volume 0.30 (night), scene eigen-fireplace "
            "(21:00-23:30); next: off at mon 23:30 (in 1h 0m)");
  // Without night_volume the sound only fades; a wrong one is refused.
  EXPECT_DOUBLE_EQ(evaluate_schedule(parse(kWeek), at(kMon, 22, 30)).volume, 1.0);
  EXPECT_NE(error_of("night_volume = 1.5\n").find("schedule.night_volume"), std::string::npos);
}

TEST(Schedule, ScenePerTimeRange) {
  const Schedule s = parse(kWeek);
  ASSERT_EQ(s.scenes.size(), 2u);
  EXPECT_EQ(evaluate_schedule(s, at(kMon, 7, 30)).scene, -1);
  EXPECT_EQ(evaluate_schedule(s, at(kMon, 17, 0)).scene, 0);
  EXPECT_EQ(evaluate_schedule(s, at(kMon, 20, 59)).scene, 0);
  EXPECT_EQ(evaluate_schedule(s, at(kMon, 21, 0)).scene, 1);
  EXPECT_EQ(s.scenes[1].scene, "eigen-fireplace");
}

TEST(Schedule, WithoutDaysAlwaysOn) {
  const Schedule s = parse("night = \"23:00-07:00\"\nnight_level = 0.25\n");
  EXPECT_FALSE(s.has_days);
  EXPECT_TRUE(evaluate_schedule(s, at(kSun, 12, 0)).on);
  EXPECT_DOUBLE_EQ(evaluate_schedule(s, at(kSun, 12, 0)).level, 1.0);
  EXPECT_DOUBLE_EQ(evaluate_schedule(s, at(kSun, 3, 0)).level, 0.25);
  // Days not named are off all day once any day is named.
  const Schedule t = parse("tue = \"10:00-11:00\"\n");
  EXPECT_FALSE(evaluate_schedule(t, at(kMon, 10, 30)).on);
  EXPECT_TRUE(evaluate_schedule(t, at(kTue, 10, 30)).on);
  EXPECT_EQ(describe_schedule(parse(""), at(kMon, 9, 0), "default"),
            "now mon 09:00: screen on, level 1.00, scene default; no on/off times (always on)");
}

TEST(Schedule, MistakesNameFileKeyAndWhatWasExpected) {
  EXPECT_NE(error_of("mon-fry = \"07:00-08:00\"\n")
                .find("schedule.mon-fry: unknown key: expected a "
                      "weekday"),
            std::string::npos);
  EXPECT_NE(error_of("mon = \"7:00-8:00\"\n").find("schedule.mon: expected time ranges"),
            std::string::npos);
  EXPECT_NE(error_of("mon = \"07:00-07:00\"\n").find("schedule.mon: expected"), std::string::npos);
  EXPECT_NE(error_of("mon = \"07:00-25:00\"\n").find("got \"07:00-25:00\""), std::string::npos);
  EXPECT_NE(error_of("mon-fri = \"off\"\nfri = \"off\"\n").find("names fri again"),
            std::string::npos);
  EXPECT_NE(error_of("mon = 7\n").find("schedule.mon: expected a string"), std::string::npos);
  EXPECT_NE(error_of("fade_in = -1\n").find("schedule.fade_in"), std::string::npos);
  EXPECT_NE(error_of("night_level = 2\n").find("schedule.night_level"), std::string::npos);
  EXPECT_NE(error_of("night = \"late\"\n").find("schedule.night: expected one time range"),
            std::string::npos);
  EXPECT_NE(error_of("[schedule.scenes]\n\"17:00-22:00\" = \"a\"\n\"21:00-23:00\" = \"b\"\n")
                .find("overlaps \"17:00-22:00\""),
            std::string::npos);
  EXPECT_NE(error_of("[schedule.scenes]\nevening = \"a\"\n").find("schedule.scenes.evening"),
            std::string::npos);
  const std::string e = error_of("mon = \"nope\"\n");
  EXPECT_NE(e.find("candela.toml"), std::string::npos) << e;
  EXPECT_EQ(error_of(kWeek), "");
  EXPECT_EQ(error_of("daily = \"00:00-24:00\"\n"), "");
}

// Unix time of a UTC date (the tests run with TZ=UTC).
int64_t utc(int y, int mo, int d, int h, int mi, int s = 0) {
  struct tm tm {};
  tm.tm_year = y - 1900;
  tm.tm_mon = mo - 1;
  tm.tm_mday = d;
  tm.tm_hour = h;
  tm.tm_min = mi;
  tm.tm_sec = s;
  return static_cast<int64_t>(timegm(&tm));
}

class KioskSchedule : public ::testing::Test {
 protected:
  void SetUp() override {
    setenv("TZ", "UTC", 1);
    tzset();
  }
};

// The fake clock drives the schedule; the screen follows it through
// set_screen (the `screen` commands' path), and a command in between wins
// until the schedule's next change. 2026-12-07 is a Monday.
TEST_F(KioskSchedule, FakeClockSwitchesTheScreen) {
  KioskOptions o;
  o.scene_label = "default";
  o.schedule = parse(kWeek);
  FakeWallClock clock(utc(2026, 12, 7, 6, 59, 58) * 1000);
  Kiosk k(std::move(o), clock);
  InputHub hub({}, WindSpec{});
  hub.set_kiosk(&k);
  k.apply_schedule();
  EXPECT_FALSE(k.screen_on());
  EXPECT_EQ(hub.answer("screen"), "off");
  EXPECT_EQ(hub.answer("schedule"),
            "now mon 06:59: screen off, level 0.00, scene default; next: on at mon 07:00 (in 2s)");
  clock.advance_ms(2000);
  k.apply_schedule();
  EXPECT_TRUE(k.screen_on());
  EXPECT_FLOAT_EQ(k.target_level(), 0.0f);  // fading in from black
  clock.advance_ms(2000);
  k.apply_schedule();
  EXPECT_FLOAT_EQ(k.target_level(), 0.5f);
  EXPECT_EQ(hub.answer("brightness 0.5"), "ok");
  EXPECT_FLOAT_EQ(k.target_level(), 0.25f);  // brightness x the schedule's level
  // A command wins until the schedule's next change...
  EXPECT_EQ(hub.answer("screen off"), "ok");
  clock.advance_ms(60'000);
  k.apply_schedule();
  EXPECT_FALSE(k.screen_on());
  EXPECT_EQ(hub.answer("screen on"), "ok");
  // ...which is 08:30's off.
  clock.set_ms(utc(2026, 12, 7, 8, 30) * 1000);
  k.apply_schedule();
  EXPECT_FALSE(k.screen_on());
  EXPECT_NE(hub.answer("state").find("\"screen\":\"off\""), std::string::npos);
  EXPECT_NE(
      hub.answer("state").find("\"screen\":\"off\",\"display\":{\"status\":\"off\",\"width\":null"),
      std::string::npos)
      << "switched off on purpose: the display says off, not waiting";
  EXPECT_NE(hub.answer("schedule").find("next: on at mon 17:00 (in 8h 30m)"), std::string::npos);
}

// A frame loop stand-in: takes each scene the kiosk hands over and says it
// was built (or fails those whose file names "fail").
class FakeLoop {
 public:
  explicit FakeLoop(Kiosk& k) : k_(k), t_([this] { run(); }) {}
  ~FakeLoop() {
    stop_ = true;
    t_.join();
  }
  std::atomic<int> taken{0};

 private:
  void run() {
    while (!stop_) {
      if (k_.scene_waiting()) {
        if (auto d = k_.take_scene()) {
          ++taken;
          k_.scene_built(d->file.find("fail") != std::string::npos ? d->file + ": GL said no" : "");
        }
      }
      k_.wait_for_wake(5);  // woken by the hand-over; the timeout only ends the test
    }
  }
  Kiosk& k_;
  std::atomic<bool> stop_{false};
  std::thread t_;
};

TEST_F(KioskSchedule, ScenesAreValidatedBeforeTheFrameLoopSeesThem) {
  TempDir d;
  const std::string broken = d.write("broken.toml", "[[element]]\nkind = \"candles\"\nbogus = 1\n");
  const std::string fail = d.write("fail.toml", "[[element]]\nkind = \"test_pattern\"\n");
  KioskOptions o;
  o.scene_label = "test-pattern";
  FakeWallClock clock(0);
  Kiosk k(std::move(o), clock);
  InputHub hub({}, WindSpec{});
  hub.set_kiosk(&k);
  FakeLoop loop(k);
  EXPECT_EQ(hub.answer("scene default"), "ok");
  EXPECT_EQ(k.status().scene, "default");
  EXPECT_EQ(loop.taken, 1);
  std::string r = hub.answer("scene no-such-scene");
  EXPECT_EQ(r.rfind("error: scene \"no-such-scene\": no such built-in scene (built in: ", 0), 0u)
      << r;
  EXPECT_NE(r.find("eigen-fireplace"), std::string::npos) << r;
  r = hub.answer("scene " + broken);
  EXPECT_NE(r.find(": element[0]."), std::string::npos) << r;
  EXPECT_NE(r.find("the running scene stays"), std::string::npos) << r;
  r = hub.answer("scene " + d.path() + "/missing.toml");
  EXPECT_EQ(r.rfind("error: ", 0), 0u) << r;
  EXPECT_EQ(loop.taken, 1);  // none of those reached the frame loop
  r = hub.answer("scene " + fail);
  EXPECT_EQ(r, "error: " + fail + ": GL said no; the running scene stays");
  EXPECT_EQ(k.status().scene, "default");
  EXPECT_NE(hub.answer("state").find("\"scene\":\"default\""), std::string::npos);
}

TEST_F(KioskSchedule, ScheduledScenesAreShownAtTheirTimes) {
  KioskOptions o;
  o.scene_label = "default";
  o.schedule = parse(kWeek);
  FakeWallClock clock(utc(2026, 12, 7, 16, 59) * 1000);
  Kiosk k(std::move(o), clock);
  FakeLoop loop(k);
  k.apply_schedule();
  EXPECT_EQ(loop.taken, 0);
  clock.set_ms(utc(2026, 12, 7, 17, 0) * 1000);
  k.apply_schedule();
  EXPECT_EQ(k.status().scene, "eigen-candle");
  clock.set_ms(utc(2026, 12, 7, 21, 0) * 1000);
  k.apply_schedule();
  EXPECT_EQ(k.status().scene, "eigen-fireplace");
  clock.set_ms(utc(2026, 12, 8, 7, 0) * 1000);
  k.apply_schedule();
  EXPECT_EQ(k.status().scene, "default");  // outside the ranges: the config's
  EXPECT_EQ(loop.taken, 3);
}

// Started inside a scene range (main() showed that range's scene): the
// config's scene comes back when the range ends.
TEST_F(KioskSchedule, StartedInARangeTheConfigSceneComesBack) {
  KioskOptions o;
  o.scene_label = "eigen-candle";
  o.config_scene = "default";
  o.schedule = parse(kWeek);
  FakeWallClock clock(utc(2026, 12, 7, 18, 0) * 1000);
  Kiosk k(std::move(o), clock);
  FakeLoop loop(k);
  k.apply_schedule();
  EXPECT_EQ(loop.taken, 0);  // already showing it
  EXPECT_NE(k.schedule_text().find("scene eigen-candle (17:00-21:00)"), std::string::npos);
  clock.set_ms(utc(2026, 12, 7, 23, 40) * 1000);
  k.apply_schedule();
  EXPECT_EQ(k.status().scene, "default");
  EXPECT_FALSE(k.screen_on());
  EXPECT_EQ(loop.taken, 1);
}

// A stand-in for HDMI-CEC: records what it was asked, in order.
class FakeSwitch final : public ScreenPowerSwitch {
 public:
  struct Log {
    std::mutex mu;
    std::condition_variable cv;
    std::string calls;
    // Waits (bounded) until the calls read `want`.
    bool wait_for(const std::string& want) {
      std::unique_lock lock(mu);
      return cv.wait_for(lock, std::chrono::seconds(5), [&] { return calls == want; });
    }
  };
  explicit FakeSwitch(Log* log) : log_(log) {}
  std::string name() const override { return "fake"; }
  bool set_power(bool on) override {
    std::lock_guard lock(log_->mu);
    log_->calls += on ? "on " : "off ";
    log_->cv.notify_all();
    return true;
  }

 private:
  Log* log_;
};

// The screen power path drives the TV switch (CEC) beside DPMS, on its own
// thread: the state at start, then every change, whoever made it.
TEST_F(KioskSchedule, ScreenChangesReachTheTvSwitch) {
  KioskOptions o;
  o.scene_label = "default";
  o.schedule = parse("mon = \"07:00-08:00\"\n");
  FakeWallClock clock(utc(2026, 12, 7, 6, 0) * 1000);
  Kiosk k(std::move(o), clock);
  InputHub hub({}, WindSpec{});
  hub.set_kiosk(&k);
  k.apply_schedule();
  FakeSwitch::Log log;
  k.start_power_switch([&] { return std::make_unique<FakeSwitch>(&log); });
  EXPECT_TRUE(log.wait_for("off ")) << log.calls;  // scheduled off at start
  clock.set_ms(utc(2026, 12, 7, 7, 0) * 1000);
  k.apply_schedule();
  EXPECT_TRUE(log.wait_for("off on ")) << log.calls;
  EXPECT_EQ(hub.answer("screen off"), "ok");
  EXPECT_TRUE(log.wait_for("off on off ")) << log.calls;
  EXPECT_EQ(hub.answer("screen off"), "ok");  // no change: nothing sent
  EXPECT_EQ(hub.answer("screen on"), "ok");
  EXPECT_TRUE(log.wait_for("off on off on ")) << log.calls;
  k.stop();
  EXPECT_EQ(k.power_switched(), 4u);
}

// No switch (no libcec, no adapter): the commands work as before.
TEST_F(KioskSchedule, NoTvSwitchIsFine) {
  KioskOptions o;
  o.scene_label = "default";
  FakeWallClock clock(0);
  Kiosk k(std::move(o), clock);
  k.start_power_switch([] { return std::unique_ptr<ScreenPowerSwitch>(); });
  InputHub hub({}, WindSpec{});
  hub.set_kiosk(&k);
  EXPECT_EQ(hub.answer("screen off"), "ok");
  EXPECT_EQ(hub.answer("screen"), "off");
  k.stop();
  EXPECT_EQ(k.power_switched(), 0u);
}

// This machine has no CEC adapter: libcec (or its absence) says so and the
// kiosk goes on with DPMS.
TEST(Cec, AbsentAdapterGivesNoSwitch) {
  auto sw = open_cec_switch();
  if (sw) GTEST_SKIP() << "a CEC adapter is present here: " << sw->name();
  EXPECT_EQ(open_cec_switch(), nullptr);  // again: still none (and logged once)
}

TEST(KioskCommands, BrightnessAndScreen) {
  KioskOptions o;
  o.scene_label = "default";
  FakeWallClock clock(0);
  Kiosk k(std::move(o), clock);
  InputHub hub({}, WindSpec{});
  EXPECT_EQ(hub.answer("screen off").rfind("error: this candela has no kiosk control", 0), 0u);
  hub.set_kiosk(&k);
  EXPECT_EQ(hub.answer("brightness"), "1.000");
  EXPECT_EQ(hub.answer("brightness 0.3"), "ok");
  EXPECT_EQ(hub.answer("brightness"), "0.300");
  EXPECT_EQ(
      hub.answer("brightness 1.5").rfind("error: brightness: expected one level in [0, 1]", 0), 0u);
  EXPECT_FLOAT_EQ(k.target_level(), 0.3f);
  EXPECT_EQ(hub.answer("screen sideways"),
            "error: screen: expected on or off, e.g. \"screen off\", got \"sideways\"");
  EXPECT_EQ(hub.answer("screen off"), "ok");
  EXPECT_FALSE(k.screen_on());
  EXPECT_EQ(hub.answer("screen"), "off");
  const std::string st = hub.answer("state");
  EXPECT_NE(st.find("\"scene\":\"default\",\"brightness\":0.3,\"screen\":\"off\""),
            std::string::npos)
      << st;
  EXPECT_NE(st.find("\"errors\":"), std::string::npos) << st;
  EXPECT_NE(st.find("\"fps\":0"), std::string::npos) << st;
  const std::string mqtt = hub.answer("state", InputHub::Origin::kMqtt);
  EXPECT_NE(mqtt.find("\"screen\":\"off\""), std::string::npos) << mqtt;
  EXPECT_NE(mqtt.find("\"fps\":"), std::string::npos) << mqtt;
  EXPECT_NE(mqtt.find("\"errors\":"), std::string::npos) << mqtt;
  EXPECT_EQ(hub.answer("schedule"),
            "no [schedule] in the config: the screen follows commands only");
  EXPECT_EQ(hub.answer("scene"),
            "error: scene: expected a built-in scene's name (e.g. \"scene eigen-fireplace\") or a "
            "scene file's path");
}

}  // namespace
}  // namespace candela
