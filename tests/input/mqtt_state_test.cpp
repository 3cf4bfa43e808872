// The MQTT state's pace (issue 34): while the wind moves the retained state
// went out ~10 times a second (77 messages in 50 s); a setting's change is
// still published at once, what moves on its own at most once a second, and
// the last value of the wind is not lost.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "input/mqtt_bridge.h"

namespace candela {
namespace {

constexpr int64_t kMs = 1'000'000;

// A state as InputHub::summary_json() writes it.
std::string state(int frame, double wind_x, const char* screen, int events = 0) {
  char b[320];
  std::snprintf(b, sizeof b,
                "{\"frame\":%d,\"step\":%d,\"fps\":60.0,\"wind\":{\"x\":%.4f,\"z\":0.0},"
                "\"volume\":0.6,\"candles_lit\":null,\"events\":%d,\"scene\":\"default\","
                "\"brightness\":1.0,\"screen\":\"%s\",\"errors\":0}",
                frame, frame, wind_x, events, screen);
  return b;
}

TEST(MqttStatePacer, TheWindMovesAtMostOnceASecondSettingsAtOnce) {
  MqttStatePacer p;
  int64_t t = 5'000 * kMs;
  EXPECT_TRUE(p.due(state(0, 0, "on"), t, false)) << "the first state";
  EXPECT_FALSE(p.due(state(6, 0, "on"), t + 100 * kMs, false)) << "the frame counter alone";
  // A gust: the wind changes at every 0.1 s check for 5 s.
  int published = 0;
  for (int i = 1; i <= 50; ++i) {
    t += 100 * kMs;
    published += p.due(state(6 * i, 0.01 * i, "on", i), t, false);
  }
  EXPECT_GE(published, 4);
  EXPECT_LE(published, 5) << "at most one a second while only the wind moves";
  // The screen switched off mid-gust: published at the next check.
  t += 100 * kMs;
  EXPECT_TRUE(p.due(state(400, 0.6, "off", 51), t, false));
  // The gust's last wind value goes out within a second, then nothing more.
  int64_t last = 0;
  for (int i = 1; i <= 20; ++i)
    if (p.due(state(400 + 6 * i, 0.61, "off", 51), t + i * 100 * kMs, false)) last = i;
  EXPECT_GE(last, 1);
  EXPECT_LE(last, 10);
  // A command's answer and the 10 s refresh always publish.
  EXPECT_TRUE(p.due(state(600, 0.61, "off", 51), t + 2'100 * kMs, true));
}

}  // namespace
}  // namespace candela
