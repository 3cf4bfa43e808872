#include "app/screen_watch.h"

#include "app/frame_pacing.h"
#include "app/frame_reports.h"
#include "app/kiosk.h"
#include "app/kiosk_post.h"
#include "app/sd_notify.h"
#include "display/display.h"
#include "input/input_hub.h"

namespace candela {

ScreenWatch::ScreenWatch(Display& display, Kiosk* kiosk, InputHub* inputs, SdNotify* notify)
    : display_(display), kiosk_(kiosk), inputs_(inputs), notify_(notify) {}

bool ScreenWatch::ready(WindField& wind, FramePacer& pace, FrameReports& reports,
                        BrightnessGlide& glide) {
  using Clock = FramePacer::Clock;
  if (kiosk_ && kiosk_->screen_on() != screen_on_) {
    screen_on_ = !screen_on_;
    display_.set_screen_power(screen_on_);
    reports.restart_rate(Clock::now());
    if (screen_on_) {
      pace.resume(Clock::now());  // no catching up on the time spent off
      glide.level = 0.0f;         // glides up from black
    } else {
      reports.screen_off();
    }
  }
  if (!screen_on_) {
    // Asleep until a command wakes it (or a quarter second, for signals and pings).
    if (inputs_) inputs_->drain(wind);
    if (notify_) notify_->idle(Clock::now());
    pace.count_asleep(Clock::now());
    kiosk_->wait_for_wake(pace.sleep_ms());
    pace.count_asleep(Clock::now());
    return false;
  }
  if (!display_.screen_present()) {
    // No monitor: waiting on the display's uevents.
    if (inputs_) inputs_->drain(wind);
    if (notify_) notify_->idle(Clock::now(), "waiting for a screen");
    reports.waiting_for_screen(screen_present_);
    screen_present_ = false;
    pace.count_asleep(Clock::now());
    display_.wait_for_screen(pace.sleep_ms());
    pace.count_asleep(Clock::now());
    return false;
  }
  pace.awake();
  if (!screen_present_) {  // a screen again: no catching up on the time without one
    screen_present_ = true;
    const auto now = Clock::now();
    pace.resume(now);
    reports.restart_rate(now);
  }
  return true;
}

}  // namespace candela
