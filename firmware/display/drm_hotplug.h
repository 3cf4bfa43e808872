// Connector hot-plug on one DRM card (the DRM display's): udev's "drm"
// uevents (a change of the card: HOTPLUG=1 from the driver's connector
// polling or interrupt, or a synthetic `change`) say when to look at the
// connectors again. Without a uevent monitor (no netlink socket allowed) the
// connectors are looked at every kReprobeMs while no screen is shown.
#pragma once

#include <sys/types.h>

#include <chrono>
#include <string>

struct udev;
struct udev_monitor;

namespace candela {

class DrmHotplug {
 public:
  static constexpr int kReprobeMs = 2000;

  // card_fd: the card's open file (its device number picks its uevents).
  DrmHotplug(int card_fd, const std::string& device);
  ~DrmHotplug();
  DrmHotplug(const DrmHotplug&) = delete;
  DrmHotplug& operator=(const DrmHotplug&) = delete;

  // Waits up to timeout_ms (0: not at all) for a change of this card. True:
  // look at the connectors again. `screen`: a screen is shown now (without
  // uevents, the connectors are re-probed only while none is).
  bool changed(int timeout_ms, bool screen);

 private:
  udev* udev_ = nullptr;
  udev_monitor* monitor_ = nullptr;
  int uevent_fd_ = -1;  // the monitor's (non-blocking); -1: re-probe every kReprobeMs
  dev_t card_devnum_ = 0;
  std::chrono::steady_clock::time_point next_reprobe_{};
};

}  // namespace candela
