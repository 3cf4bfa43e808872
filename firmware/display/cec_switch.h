// Switching the TV itself over HDMI-CEC, beside DPMS (issue 16): many TVs
// ignore a lost signal for minutes, or never sleep on it; CEC "standby" and
// "image view on" reach them. Through libcec (Debian libcec6), loaded with
// dlopen at run time, so the kiosk runs (DPMS only) where it is not
// installed or the board has no CEC adapter; the build needs only its
// headers (libcec-dev; without them CEC is compiled out). A CEC call can
// take seconds on the bus: never call these on the frame loop (the kiosk
// has a thread for it, app/kiosk.h).
#pragma once

#include <memory>
#include <string>

namespace candela {

// A switch for the screen's power beside the display's own (DPMS).
class ScreenPowerSwitch {
 public:
  virtual ~ScreenPowerSwitch() = default;
  virtual std::string name() const = 0;
  // The TV on (and showing us) or to standby. False: the bus refused (logged).
  virtual bool set_power(bool on) = 0;
};

// libcec's first adapter, opened; null when libcec or an adapter is absent
// or it cannot be opened: said once per process in the log (info), after
// which the kiosk switches the screen with DPMS only.
std::unique_ptr<ScreenPowerSwitch> open_cec_switch();

}  // namespace candela
