// Finding somewhere to show frames on KMS: a card with a connected
// connector, a CRTC that can drive it, that CRTC's primary plane, a mode,
// and what the plane accepts. Used by the DRM display backend.
#pragma once

#include <xf86drmMode.h>

#include <cstdint>
#include <string>
#include <vector>

#include "display/display.h"

namespace candela {

// Atomic property ids of the objects the backend programs (0: not found).
struct KmsPropertyIds {
  uint32_t connector_crtc_id = 0;
  uint32_t crtc_mode_id = 0, crtc_active = 0;
  uint32_t plane_fb_id = 0, plane_crtc_id = 0;
  uint32_t plane_src_x = 0, plane_src_y = 0, plane_src_w = 0, plane_src_h = 0;
  uint32_t plane_crtc_x = 0, plane_crtc_y = 0, plane_crtc_w = 0, plane_crtc_h = 0;
  bool complete() const;
};

struct KmsOutput {
  int fd = -1;  // owned; O_RDWR | O_CLOEXEC, DRM master
  std::string device;
  std::string driver;
  uint32_t connector_id = 0;
  std::string connector_name;  // e.g. HDMI-A-1, Virtual-1
  uint32_t crtc_id = 0;
  uint32_t plane_id = 0;  // the CRTC's primary plane; 0 without universal planes
  drmModeModeInfo mode{};
  bool atomic = false;            // atomic modesetting usable (caps and properties present)
  bool addfb2_modifiers = false;  // DRM_CAP_ADDFB2_MODIFIERS
  std::vector<uint64_t>
      modifiers;  // the plane's IN_FORMATS modifiers for the format; empty: unknown
  KmsPropertyIds props;

  KmsOutput() = default;
  KmsOutput(const KmsOutput&) = delete;
  KmsOutput& operator=(const KmsOutput&) = delete;
  KmsOutput(KmsOutput&& o) noexcept;
  KmsOutput& operator=(KmsOutput&&) = delete;
  ~KmsOutput();
};

// Opens options.drm_device, or the first /dev/dri/card* with a connected
// connector (render-only devices are skipped), becomes DRM master, and picks
// the mode matching options.width/height/refresh_hz or the preferred one.
// `format` (a DRM fourcc) must be scanned out by the primary plane. Set
// CANDELA_DRM_LEGACY=1 in the environment to force the legacy (non-atomic)
// path. With `wait_for_screen`, a KMS card with nothing connected (the first
// one) is returned as it is, master, with connector_id 0: a screen plugged in
// later is found by probe_kms_connector(). Throws RuntimeError naming every
// device tried and why it was skipped.
KmsOutput open_kms_output(const DisplayOptions& options, uint32_t format,
                          bool wait_for_screen = false);

// Looks at out.fd's connectors again: the first connected one, its CRTC,
// primary plane, mode (chosen as above), modifiers and atomic properties go
// into `out`. False with `why` ("nothing connected (...)", ...) otherwise,
// leaving `out` as it was. The mode is chosen by choose_mode (drm_mode.h).
bool probe_kms_connector(KmsOutput& out, const DisplayOptions& options, uint32_t format,
                         std::string& why);

}  // namespace candela
