// What the control socket and MQTT ask of the kiosk beyond the wind and the
// volume: scene, brightness, screen power, reload and the schedule. The
// runtime (app/kiosk.h) implements it; InputHub::answer hands those commands
// here, so both channels accept exactly the same. Called on the input
// thread and on MQTT's client thread, never on the frame loop's.
#pragma once

#include <string>

#include "input/control_channel.h"

namespace candela {

// What `state` and MQTT's state topic report of the kiosk.
struct KioskStatus {
  std::string scene;        // the built-in name or the path last shown
  double brightness = 1.0;  // the master brightness asked for (0..1)
  bool screen_on = true;
  double fps = 0.0;  // frames presented per second, over about the last second
  // Where the frames go (`state`'s "display"): "starting" (no frame shown
  // yet), "drawing" (frames shown at width x height), "waiting" (no screen
  // connected: DRM waits for one to be plugged in or switched on), "off"
  // (switched off on purpose: `screen off` or the schedule).
  std::string display = "starting";
  int width = 0, height = 0;  // of the frames drawn last; 0 before the first
};

class KioskControl {
 public:
  virtual ~KioskControl() = default;
  // kScene, kBrightness, kScreen, kReload, kSchedule -> one reply line
  // ("ok", a value, "error: ...").
  virtual std::string command(const ControlCommand& c) = 0;
  virtual KioskStatus status() const = 0;
};

}  // namespace candela
