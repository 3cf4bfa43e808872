// The kiosk's [schedule] (app/config_file.h): when the screen is on, how it
// fades in and out, how much it dims at night and which scene each time of
// day shows. Pure: evaluate() maps a local time to what should be showing,
// so tests drive it with any clock (core/clock.h's WallClock).
//   [schedule]
//   mon-fri = "07:00-08:30, 17:00-23:30"   # on-times per weekday (or a day range,
//   sat-sun = "09:00-01:00"                #   or "daily"); an end before the start
//                                          #   runs past midnight; "off": all day off
//   fade_in = 3                            # s, 0..3600: up from black after an on-time
//   fade_out = 10                          # s, 0..3600: down to black before an off-time
//   night = "22:00-06:30"                  # dimmed every day in this range
//   night_level = 0.4                      # the brightness then (0..1)
//   night_volume = 0.3                     # the sound's volume then (0..1; default 1):
//                                          #   it fades in and out with the picture
//   [schedule.scenes]                      # a scene per time range, every day;
//   "17:00-21:00" = "eigen-candle"         #   outside them: the config's scene
//   "21:00-23:30" = "eigen-fireplace"
// With no day key the screen is always on (the schedule then only dims or
// picks scenes); with any, days not named are off all day.
#pragma once

#include <bitset>
#include <cstdint>
#include <string>
#include <vector>

namespace candela {

class ParamReader;

inline constexpr int kMinutesPerDay = 24 * 60;
inline constexpr int kMinutesPerWeek = 7 * kMinutesPerDay;

struct Schedule {
  bool present = false;             // the config has a [schedule] table
  bool has_days = false;            // some day key: on-times apply
  std::bitset<kMinutesPerWeek> on;  // minute of the week (Monday 00:00 = 0) -> screen on
  int fade_in_s = 3;
  int fade_out_s = 10;
  std::bitset<kMinutesPerDay> night;  // minute of the day -> dimmed
  double night_level = 0.5;
  double night_volume = 1.0;
  struct SceneRange {
    std::string range;  // as written, "17:00-21:00"
    std::bitset<kMinutesPerDay> minutes;
    std::string scene;  // a built-in name or a path (resolved against the config's folder)
  };
  std::vector<SceneRange> scenes;
};

// Reads [schedule] (a reader on the table; `present`: the file has it).
// Throws ConfigError naming the file, the key and what was expected. Scene
// paths are resolved against `config_file`'s folder; a scene is only
// checked when shown (a broken one is logged and the old one stays).
Schedule parse_schedule(ParamReader& reader, bool present, const std::string& config_file);

// A local time: the weekday (0 Monday .. 6 Sunday) and seconds since local
// midnight (0 .. 86399).
struct LocalTime {
  int weekday = 0;
  int second_of_day = 0;
};
// The local time of a Unix time (localtime_r: $TZ or /etc/localtime).
LocalTime local_time(int64_t unix_s);

struct ScheduleNow {
  bool on = true;         // the screen should be on
  double level = 1.0;     // the brightness multiplier now: fades and night (0..1)
  double volume = 1.0;    // the volume multiplier now: the same fades, night_volume (0..1)
  int scene = -1;         // index into Schedule::scenes; -1: the config's scene
  bool has_next = false;  // a change of on/off ahead (within a week)
  bool next_on = false;   // what it changes to
  int64_t next_in_s = 0;  // seconds until it
};
ScheduleNow evaluate_schedule(const Schedule& s, const LocalTime& t);
// The scene to show now: the schedule's range's where one names a scene,
// else `configured` (the config's or --scene's). Used at start-up, on reload
// and as the schedule changes, so all three agree.
const std::string& scheduled_scene(const Schedule& s, const ScheduleNow& now,
                                   const std::string& configured);

// One line for the `schedule` command: "screen on (fading in), level 1.00,
// scene eigen-candle (17:00-21:00); next: off at Tue 23:30 (in 2h 5m)".
std::string describe_schedule(const Schedule& s, const LocalTime& t, const std::string& scene);

}  // namespace candela
