// The kiosk's DRM mode choice (display/drm_kms.h), at start and again after
// a hot-plug: the functions probe_kms_connector and DrmDisplay::reprobe call,
// fed with the mode lists two different monitors give. (Debian 12's vkms
// lists the same modes on every plug, so the virtual board cannot show a
// monitor with another preferred mode; board_drm_hotplug checks the real
// re-plug with the same one.)
#include <gtest/gtest.h>
#include <xf86drmMode.h>

#include <cstdio>
#include <vector>

#include "display/drm_mode.h"

namespace candela {
namespace {

// A mode as a connector lists it (CEA-like timings: what matters here is
// that two modes of one size differ in their timings).
drmModeModeInfo mode(int w, int h, int hz, bool preferred = false) {
  drmModeModeInfo m{};
  m.hdisplay = static_cast<uint16_t>(w);
  m.vdisplay = static_cast<uint16_t>(h);
  m.htotal = static_cast<uint16_t>(w + w / 5);
  m.vtotal = static_cast<uint16_t>(h + h / 20);
  m.vrefresh = static_cast<uint32_t>(hz);
  m.clock = static_cast<uint32_t>(m.htotal * m.vtotal * hz / 1000);
  m.type = DRM_MODE_TYPE_DRIVER | (preferred ? DRM_MODE_TYPE_PREFERRED : 0);
  std::snprintf(m.name, sizeof m.name, "%dx%d", w, h);
  return m;
}

// What a mode is, for messages: "1920x1080@60".
std::string size_of(const drmModeModeInfo& m) {
  return std::to_string(m.hdisplay) + "x" + std::to_string(m.vdisplay) + "@" +
         std::to_string(m.vrefresh);
}

const drmModeModeInfo& choose(const std::vector<drmModeModeInfo>& modes, const DisplayOptions& o) {
  return choose_mode(modes.data(), static_cast<int>(modes.size()), o, "HDMI-A-1");
}

// A full-HD TV, then a 5:4 monitor on the same HDMI connector (id 42).
const std::vector<drmModeModeInfo> kTv = {mode(1920, 1080, 60, true), mode(1920, 1080, 50),
                                          mode(1280, 720, 60), mode(1024, 768, 60)};
const std::vector<drmModeModeInfo> kMonitor = {mode(1280, 1024, 60, true), mode(1920, 1080, 60),
                                               mode(1024, 768, 75), mode(1024, 768, 60),
                                               mode(800, 600, 60)};
const std::vector<drmModeModeInfo> kSmall = {mode(800, 600, 60, true), mode(640, 480, 60)};

TEST(DrmMode, ReplugWithAnotherPreferredModeSetsThatMode) {
  const DisplayOptions o;  // no [display] size: the monitor's preferred mode
  const drmModeModeInfo tv = choose(kTv, o);
  EXPECT_EQ(size_of(tv), "1920x1080@60");
  // The TV unplugged (screen gone), the monitor plugged in.
  const drmModeModeInfo monitor = choose(kMonitor, o);
  EXPECT_EQ(size_of(monitor), "1280x1024@60") << "the new monitor's preferred mode";
  EXPECT_TRUE(needs_new_mode(false, 42, tv, 42, monitor)) << "a screen appeared";
  // Swapped between two events (our connector never seen disconnected).
  EXPECT_TRUE(needs_new_mode(true, 42, tv, 42, monitor)) << "another mode on the same connector";
  // A hot-plug event for something else: the same TV still there.
  EXPECT_FALSE(needs_new_mode(true, 42, tv, 42, choose(kTv, o))) << "nothing to set again";
  EXPECT_TRUE(needs_new_mode(true, 42, tv, 43, choose(kTv, o))) << "another connector";
}

TEST(DrmMode, ConfiguredSizeWinsWhereTheMonitorHasIt) {
  DisplayOptions o;
  o.width = 1920;
  o.height = 1080;
  const drmModeModeInfo tv = choose(kTv, o);
  EXPECT_EQ(size_of(tv), "1920x1080@60") << "the preferred one among equals";
  const drmModeModeInfo monitor = choose(kMonitor, o);
  EXPECT_EQ(size_of(monitor), "1920x1080@60") << "the configured size, not the preferred 1280x1024";
  EXPECT_FALSE(monitor.type & DRM_MODE_TYPE_PREFERRED);
  // The same timings on both: no new modeset needed when they swap under one event.
  EXPECT_FALSE(needs_new_mode(true, 42, tv, 42, monitor))
      << "the same timings (only the preferred flag differs)";
  // A monitor without that size: its preferred mode (and a warning).
  EXPECT_EQ(size_of(choose(kSmall, o)), "800x600@60");

  o.width = 1024;
  o.height = 768;
  EXPECT_EQ(size_of(choose(kTv, o)), "1024x768@60");
  EXPECT_EQ(size_of(choose(kMonitor, o)), "1024x768@75") << "the highest refresh of that size";
  EXPECT_TRUE(needs_new_mode(true, 42, choose(kTv, o), 42, choose(kMonitor, o)))
      << "same size, other timings: set again";
  o.refresh_hz = 60;
  EXPECT_EQ(size_of(choose(kMonitor, o)), "1024x768@60") << "the configured refresh";

  DisplayOptions rate_only;
  rate_only.refresh_hz = 50;
  EXPECT_EQ(size_of(choose(kTv, rate_only)), "1920x1080@50") << "the preferred size at 50 Hz";
  EXPECT_EQ(size_of(choose(kMonitor, rate_only)), "1280x1024@60")
      << "no 1280x1024@50: the preferred mode";
}

}  // namespace
}  // namespace candela
