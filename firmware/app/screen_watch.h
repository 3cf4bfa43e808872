// Whether the frame loop can show a frame now (app/frame_loop.cpp): the
// kiosk's screen power (a command or the [schedule] turns it off) and the
// display's monitor (DRM hot-plug). While neither lets a frame be seen,
// nothing is drawn and the animation pauses, but the inputs are served, the
// watchdog pinged, and the loop sleeps until woken.
#pragma once

namespace candela {

struct BrightnessGlide;
class Display;
class FramePacer;
class FrameReports;
class InputHub;
class Kiosk;
class SdNotify;
class WindField;

class ScreenWatch {
 public:
  // kiosk, inputs, notify may be null.
  ScreenWatch(Display& display, Kiosk* kiosk, InputHub* inputs, SdNotify* notify);

  // Before each frame. False: nothing can be shown now; the inputs were
  // drained into `wind` and a wait of at most pace.sleep_ms() done (the
  // caller loops). A screen back on glides up from black and, like a screen
  // plugged in again, does not catch up on the time without it.
  bool ready(WindField& wind, FramePacer& pace, FrameReports& reports, BrightnessGlide& glide);
  bool screen_on() const { return screen_on_; }

 private:
  Display& display_;
  Kiosk* kiosk_;
  InputHub* inputs_;
  SdNotify* notify_;
  bool screen_on_ = true;
  bool screen_present_ = true;  // the display has somewhere to show frames
};

}  // namespace candela
