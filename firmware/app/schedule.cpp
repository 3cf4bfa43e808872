#include "app/schedule.h"

#include <time.h>

#include <algorithm>
#include <cstdio>

#include "params/params.h"

namespace candela {
namespace {

const char* const kDays[] = {"mon", "tue", "wed", "thu", "fri", "sat", "sun"};

int day_index(const std::string& d) {
  for (int i = 0; i < 7; ++i)
    if (d == kDays[i]) return i;
  return -1;
}

// "HH:MM" -> minutes (00:00 .. 24:00); -1 if malformed.
int parse_hhmm(const std::string& s) {
  if (s.size() != 5 || s[2] != ':') return -1;
  for (int i : {0, 1, 3, 4})
    if (s[static_cast<size_t>(i)] < '0' || s[static_cast<size_t>(i)] > '9') return -1;
  const int h = (s[0] - '0') * 10 + (s[1] - '0');
  const int m = (s[3] - '0') * 10 + (s[4] - '0');
  if (m > 59 || h > 24 || (h == 24 && m != 0)) return -1;
  return h * 60 + m;
}

std::string trim(const std::string& s) {
  size_t a = 0, b = s.size();
  while (a < b && (s[a] == ' ' || s[a] == '\t')) ++a;
  while (b > a && (s[b - 1] == ' ' || s[b - 1] == '\t')) --b;
  return s.substr(a, b - a);
}

// "HH:MM-HH:MM" -> [from, to) in minutes; to < from runs past midnight.
bool parse_range(const std::string& text, int& from, int& to) {
  const std::string t = trim(text);
  if (t.size() != 11 || t[5] != '-') return false;
  from = parse_hhmm(t.substr(0, 5));
  to = parse_hhmm(t.substr(6));
  if (from < 0 || to < 0 || from == to || from == kMinutesPerDay) return false;
  if (to == 0) to = kMinutesPerDay;  // "22:00-00:00": up to midnight
  return true;
}

const char* const kRangeHelp =
    "expected time ranges \"HH:MM-HH:MM\" separated by commas (an end before the start runs "
    "past midnight), or \"off\", e.g. \"07:00-08:30, 17:00-23:30\"";

std::string hhmm(int minute) {
  char b[8];
  std::snprintf(b, sizeof b, "%02d:%02d", minute / 60 % 24, minute % 60);
  return b;
}

std::string duration(int64_t s) {
  char b[48];
  if (s >= 86400)
    std::snprintf(b, sizeof b, "%lldd %lldh", static_cast<long long>(s / 86400),
                  static_cast<long long>(s % 86400 / 3600));
  else if (s >= 3600)
    std::snprintf(b, sizeof b, "%lldh %lldm", static_cast<long long>(s / 3600),
                  static_cast<long long>(s % 3600 / 60));
  else if (s >= 60)
    std::snprintf(b, sizeof b, "%lldm %llds", static_cast<long long>(s / 60),
                  static_cast<long long>(s % 60));
  else
    std::snprintf(b, sizeof b, "%llds", static_cast<long long>(s));
  return b;
}

}  // namespace

Schedule parse_schedule(ParamReader& r, bool present, const std::string& config_file) {
  Schedule s;
  s.present = present;
  if (!present) {
    r.finish();
    return s;
  }
  std::bitset<7> named;
  for (const std::string& key : r.keys()) {
    if (key == "fade_in" || key == "fade_out" || key == "night" || key == "night_level" ||
        key == "night_volume" || key == "scenes")
      continue;
    // A day, a range of days ("mon-fri", "fri-mon" wraps) or "daily".
    int d0 = -1, d1 = -1;
    if (key == "daily") {
      d0 = 0;
      d1 = 6;
    } else if (const size_t dash = key.find('-'); dash != std::string::npos) {
      d0 = day_index(key.substr(0, dash));
      d1 = day_index(key.substr(dash + 1));
    } else {
      d0 = d1 = day_index(key);
    }
    if (d0 < 0 || d1 < 0)
      r.fail(key,
             "unknown key: expected a weekday (mon tue wed thu fri sat sun), a range of them "
             "(\"mon-fri\"), \"daily\", or fade_in, fade_out, night, night_level, night_volume, "
             "scenes");
    std::vector<int> days;
    for (int d = d0;; d = (d + 1) % 7) {
      days.push_back(d);
      if (d == d1) break;
    }
    for (int d : days) {
      if (named[static_cast<size_t>(d)])
        r.fail(key, std::string("names ") + kDays[d] + " again: each day may be in one key only");
      named.set(static_cast<size_t>(d));
    }
    const std::string text = r.string(key, "");
    if (trim(text) == "off") continue;
    size_t at = 0;
    while (at <= text.size()) {
      const size_t comma = std::min(text.find(',', at), text.size());
      int from = 0, to = 0;
      if (!parse_range(text.substr(at, comma - at), from, to))
        r.fail(key, std::string(kRangeHelp) + ", got \"" + echo_value(text) + "\"");
      if (to < from) to += kMinutesPerDay;
      for (int d : days)
        for (int m = from; m < to; ++m)
          s.on.set(static_cast<size_t>((d * kMinutesPerDay + m) % kMinutesPerWeek));
      at = comma + 1;
    }
  }
  s.has_days = named.any();
  s.fade_in_s = static_cast<int>(r.integer("fade_in", s.fade_in_s, 0, 3600));
  s.fade_out_s = static_cast<int>(r.integer("fade_out", s.fade_out_s, 0, 3600));
  s.night_level = r.number("night_level", s.night_level, 0.0, 1.0);
  s.night_volume = r.number("night_volume", s.night_volume, 0.0, 1.0);
  if (r.has("night")) {
    const std::string text = r.string("night", "");
    int from = 0, to = 0;
    if (!parse_range(text, from, to))
      r.fail("night", "expected one time range \"HH:MM-HH:MM\", e.g. \"22:00-06:30\", got \"" +
                          echo_value(text) + "\"");
    if (to < from) to += kMinutesPerDay;
    for (int m = from; m < to; ++m) s.night.set(static_cast<size_t>(m % kMinutesPerDay));
  }
  ParamReader scenes = r.table("scenes");
  for (const std::string& key : scenes.keys()) {
    Schedule::SceneRange sr;
    int from = 0, to = 0;
    if (!parse_range(key, from, to))
      scenes.fail(key,
                  "expected a time range \"HH:MM-HH:MM\" as the key, e.g. \"17:00-21:00\" = "
                  "\"eigen-candle\"");
    if (to < from) to += kMinutesPerDay;
    for (int m = from; m < to; ++m) sr.minutes.set(static_cast<size_t>(m % kMinutesPerDay));
    for (const auto& other : s.scenes)
      if ((other.minutes & sr.minutes).any())
        scenes.fail(key, "overlaps \"" + other.range + "\": expected time ranges apart");
    sr.range = key;
    sr.scene = scenes.string(key, "");
    if (sr.scene.empty())
      scenes.fail(key, "expected a built-in scene's name or a scene file's path");
    // A name without '/' or ".toml" is a built-in scene; a path is the config's.
    if (sr.scene.find('/') != std::string::npos || sr.scene.ends_with(".toml"))
      sr.scene = resolve_relative(config_file, sr.scene);
    s.scenes.push_back(std::move(sr));
  }
  scenes.finish();
  for (const std::string& key : r.keys()) r.consume(key);
  r.finish();
  return s;
}

LocalTime local_time(int64_t unix_s) {
  const time_t t = static_cast<time_t>(unix_s);
  struct tm tm {};
  localtime_r(&t, &tm);
  LocalTime lt;
  lt.weekday = (tm.tm_wday + 6) % 7;  // tm: 0 is Sunday
  lt.second_of_day = tm.tm_hour * 3600 + tm.tm_min * 60 + tm.tm_sec;
  return lt;
}

ScheduleNow evaluate_schedule(const Schedule& s, const LocalTime& t) {
  ScheduleNow n;
  const int minute_of_day = t.second_of_day / 60;
  const int sec = t.second_of_day % 60;
  const int week_minute = t.weekday * kMinutesPerDay + minute_of_day;
  for (size_t i = 0; i < s.scenes.size(); ++i)
    if (s.scenes[i].minutes[static_cast<size_t>(minute_of_day)]) n.scene = static_cast<int>(i);
  const bool night = s.night[static_cast<size_t>(minute_of_day)];
  double fade = 1.0;  // the fades' share, the same for picture and sound
  if (!s.has_days) {
    n.level = night ? s.night_level : 1.0;
    n.volume = night ? s.night_volume : 1.0;
    return n;
  }
  auto on_at = [&](int m) {
    return s.on[static_cast<size_t>(((m % kMinutesPerWeek) + kMinutesPerWeek) % kMinutesPerWeek)];
  };
  n.on = on_at(week_minute);
  // Minutes to the next change and since the last one (within a week).
  int ahead = 1;
  while (ahead <= kMinutesPerWeek && on_at(week_minute + ahead) == n.on) ++ahead;
  int behind = 0;
  while (behind < kMinutesPerWeek && on_at(week_minute - behind - 1) == n.on) ++behind;
  if (ahead <= kMinutesPerWeek) {
    n.has_next = true;
    n.next_on = !n.on;
    n.next_in_s = int64_t{ahead} * 60 - sec;
  }
  if (n.on) {
    // Fading in after the on-time, out before the off-time.
    const int64_t since = int64_t{behind} * 60 + sec;
    if (behind < kMinutesPerWeek && s.fade_in_s > 0 && since < s.fade_in_s)
      fade *= static_cast<double>(since) / s.fade_in_s;
    if (n.has_next && s.fade_out_s > 0 && n.next_in_s < s.fade_out_s)
      fade *= static_cast<double>(n.next_in_s) / s.fade_out_s;
  } else {
    fade = 0.0;
  }
  n.level = std::clamp(fade * (night ? s.night_level : 1.0), 0.0, 1.0);
  n.volume = std::clamp(fade * (night ? s.night_volume : 1.0), 0.0, 1.0);
  return n;
}

const std::string& scheduled_scene(const Schedule& s, const ScheduleNow& now,
                                   const std::string& configured) {
  return now.scene >= 0 ? s.scenes[static_cast<size_t>(now.scene)].scene : configured;
}

std::string describe_schedule(const Schedule& s, const LocalTime& t, const std::string& scene) {
  char b[256];
  if (!s.present) return "no [schedule] in the config: the screen follows commands only";
  const ScheduleNow n = evaluate_schedule(s, t);
  std::string out = std::string("now ") + kDays[t.weekday] + " " + hhmm(t.second_of_day / 60) +
                    ": screen " + (n.on ? "on" : "off");
  std::snprintf(b, sizeof b, ", level %.2f", n.level);
  out += b;
  if (s.night_volume != 1.0) {  // a sound schedule: say where it stands
    std::snprintf(b, sizeof b, ", volume %.2f", n.volume);
    out += b;
  }
  if (n.on && s.night[static_cast<size_t>(t.second_of_day / 60)]) out += " (night)";
  out += ", scene " + (n.scene >= 0 ? s.scenes[static_cast<size_t>(n.scene)].scene + " (" +
                                          s.scenes[static_cast<size_t>(n.scene)].range + ")"
                                    : scene);
  if (!s.has_days) {
    out += "; no on/off times (always on)";
  } else if (n.has_next) {
    const int at = (t.second_of_day + static_cast<int>(n.next_in_s % 86400)) / 60;
    const int day = (t.weekday + (t.second_of_day + static_cast<int>(n.next_in_s)) / 86400) % 7;
    out += std::string("; next: ") + (n.next_on ? "on" : "off") + " at " + kDays[day] + " " +
           hhmm(at) + " (in " + duration(n.next_in_s) + ")";
  } else {
    out += n.on ? "; on all week" : "; off all week";
  }
  return out;
}

}  // namespace candela
