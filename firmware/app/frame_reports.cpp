#include "app/frame_reports.h"

#include "app/frame_stats.h"
#include "app/kiosk.h"
#include "app/sd_notify.h"

namespace candela {

FrameReports::FrameReports(FrameStats* stats, Kiosk* kiosk, SdNotify* notify,
                           Clock::time_point start)
    : stats_(stats), kiosk_(kiosk), notify_(notify), last_present_(start), rate_since_(start) {}

void FrameReports::presented(uint64_t index, Clock::time_point begin, Clock::time_point end, int w,
                             int h) {
  if (stats_) {
    const double work = std::chrono::duration<double, std::milli>(end - begin).count();
    const double interval = std::chrono::duration<double, std::milli>(end - last_present_).count();
    stats_->add(index == 0 ? work : interval, work);
    if (index == 0) stats_->first_presented(end);
  }
  last_present_ = end;
  if (kiosk_) {
    if (w != shown_w_ || h != shown_h_) {  // first, or a new mode
      shown_w_ = w;
      shown_h_ = h;
      kiosk_->set_output(Kiosk::Output::kDrawing, w, h);
    }
    ++rate_frames_;
    const double window = std::chrono::duration<double>(end - rate_since_).count();
    if (window >= 1.0) {
      kiosk_->set_fps(static_cast<float>(static_cast<double>(rate_frames_) / window));
      restart_rate(end);
    }
  }
  // Only here, after a present: a loop stuck anywhere stops the watchdog pings.
  if (notify_) notify_->frame_presented(index + 1, end);
}

void FrameReports::restart_rate(Clock::time_point now) {
  rate_frames_ = 0;
  rate_since_ = now;
}

void FrameReports::screen_off() {
  if (kiosk_) kiosk_->set_fps(0.0f);
}

void FrameReports::waiting_for_screen(bool first) {
  if (kiosk_ && first) {
    kiosk_->set_fps(0.0f);
    kiosk_->set_output(Kiosk::Output::kWaiting, shown_w_, shown_h_);
  }
  shown_w_ = shown_h_ = 0;
}

}  // namespace candela
