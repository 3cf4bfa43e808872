// What the frame loop reports after each presented frame (app/frame_loop.cpp):
// --bench statistics, the kiosk's state (the size frames are drawn at, the
// frame rate over each second, "waiting for a screen") and systemd's
// watchdog. No GL, no allocation.
#pragma once

#include <chrono>
#include <cstdint>

namespace candela {

class FrameStats;
class Kiosk;
class SdNotify;

class FrameReports {
 public:
  using Clock = std::chrono::steady_clock;

  // Any may be null (nothing reported there). `start`: when the loop began.
  FrameReports(FrameStats* stats, Kiosk* kiosk, SdNotify* notify, Clock::time_point start);

  // Frame `index` (0 first) was presented: drawn from `begin` to `end` at w x h.
  void presented(uint64_t index, Clock::time_point begin, Clock::time_point end, int w, int h);
  // The frame rate is measured again from `now` (the screen back on or plugged in).
  void restart_rate(Clock::time_point now);
  // The screen went off: no frame rate.
  void screen_off();
  // No monitor: no frame rate, "waiting" with the last size drawn at (once);
  // the size is told again when frames are drawn.
  void waiting_for_screen(bool first);

 private:
  FrameStats* stats_;
  Kiosk* kiosk_;
  SdNotify* notify_;
  Clock::time_point last_present_, rate_since_;
  uint64_t rate_frames_ = 0;
  int shown_w_ = 0, shown_h_ = 0;  // the size the kiosk was last told frames are drawn at
};

}  // namespace candela
