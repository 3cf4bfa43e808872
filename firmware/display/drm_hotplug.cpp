#include "display/drm_hotplug.h"

#include <libudev.h>
#include <poll.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <thread>

#include "core/log.h"

namespace candela {

DrmHotplug::DrmHotplug(int card_fd, const std::string& device) {
  struct stat st {};
  if (fstat(card_fd, &st) == 0) card_devnum_ = st.st_rdev;
  udev_ = udev_new();
  // udevd's events where it runs (after its rules); the kernel's otherwise
  // (a container or the virtual board without udevd).
  const char* source = access("/run/udev/control", F_OK) == 0 ? "udev" : "kernel";
  if (udev_) monitor_ = udev_monitor_new_from_netlink(udev_, source);
  if (!monitor_ || udev_monitor_filter_add_match_subsystem_devtype(monitor_, "drm", nullptr) < 0 ||
      udev_monitor_enable_receiving(monitor_) < 0) {
    LOG_WARN(
        "drm: cannot listen for hot-plug uevents (%s): without a screen the connectors are "
        "looked at every %d ms instead",
        std::strerror(errno), kReprobeMs);
    if (monitor_) udev_monitor_unref(monitor_);
    monitor_ = nullptr;
    return;
  }
  uevent_fd_ = udev_monitor_get_fd(monitor_);
  LOG_INFO("drm: following connector hot-plug on %s through %s uevents", device.c_str(), source);
}

DrmHotplug::~DrmHotplug() {
  if (monitor_) udev_monitor_unref(monitor_);
  if (udev_) udev_unref(udev_);
}

bool DrmHotplug::changed(int timeout_ms, bool screen) {
  if (uevent_fd_ < 0) {
    if (screen || timeout_ms <= 0) return false;
    const auto now = std::chrono::steady_clock::now();
    if (now < next_reprobe_) {
      std::this_thread::sleep_for(
          std::min(std::chrono::milliseconds(timeout_ms),
                   std::chrono::duration_cast<std::chrono::milliseconds>(next_reprobe_ - now)));
      return false;
    }
    next_reprobe_ = now + std::chrono::milliseconds(kReprobeMs);
    return true;
  }
  pollfd p{uevent_fd_, POLLIN, 0};
  if (poll(&p, 1, timeout_ms) <= 0 || !(p.revents & POLLIN)) return false;
  bool ours = false;
  while (udev_device* d = udev_monitor_receive_device(monitor_)) {
    const char* action = udev_device_get_action(d);
    if (udev_device_get_devnum(d) == card_devnum_ && action && std::strcmp(action, "change") == 0)
      ours = true;
    udev_device_unref(d);
  }
  return ours;
}

}  // namespace candela
