// The DRM display's legacy path (drivers without atomic modesetting, or
// CANDELA_DRM_LEGACY=1): drmModeSetCrtc, drmModePageFlip, the DPMS property.
#include <xf86drm.h>

#include <cerrno>
#include <cstring>
#include <string>

#include "core/error.h"
#include "core/log.h"
#include "display/drm_commit.h"
#include "display/drm_mode.h"

namespace candela {

bool DrmCommit::legacy_modeset(uint32_t fb) {
  uint32_t connector = out_.connector_id;
  if (drmModeSetCrtc(out_.fd, out_.crtc_id, fb, 0, 0, &connector, 1, &out_.mode) != 0) {
    if (is_master_error(errno)) return false;
    throw RuntimeError("drm: cannot set mode " + describe_mode(out_.mode) + " on " +
                       out_.connector_name + ": " + std::strerror(errno));
  }
  ++modesets_;
  LOG_INFO("drm: legacy modeset %s on %s done", describe_mode(out_.mode).c_str(),
           out_.connector_name.c_str());
  return true;
}

bool DrmCommit::legacy_flip(uint32_t fb, void* user_data) {
  if (drmModePageFlip(out_.fd, out_.crtc_id, fb, DRM_MODE_PAGE_FLIP_EVENT, user_data) != 0) {
    if (is_master_error(errno)) return false;
    throw RuntimeError("drm: page flip on " + out_.connector_name +
                       " failed: " + std::strerror(errno));
  }
  return true;
}

void DrmCommit::legacy_crtc_off() {
  drmModeSetCrtc(out_.fd, out_.crtc_id, 0, 0, 0, nullptr, 0, nullptr);
}

bool DrmCommit::set_dpms(bool on) {
  drmModeObjectProperties* props =
      drmModeObjectGetProperties(out_.fd, out_.connector_id, DRM_MODE_OBJECT_CONNECTOR);
  uint32_t dpms = 0;
  for (uint32_t i = 0; props && i < props->count_props && !dpms; ++i) {
    drmModePropertyRes* p = drmModeGetProperty(out_.fd, props->props[i]);
    if (p && std::strcmp(p->name, "DPMS") == 0) dpms = p->prop_id;
    drmModeFreeProperty(p);
  }
  drmModeFreeObjectProperties(props);
  if (!dpms) {
    LOG_WARN("drm: %s has no DPMS property; the screen stays lit (showing black)",
             out_.connector_name.c_str());
    return false;
  }
  if (drmModeConnectorSetProperty(out_.fd, out_.connector_id, dpms,
                                  on ? DRM_MODE_DPMS_ON : DRM_MODE_DPMS_OFF) != 0) {
    LOG_WARN("drm: DPMS %s on %s failed: %s", on ? "On" : "Off", out_.connector_name.c_str(),
             std::strerror(errno));
    return false;
  }
  return true;
}

}  // namespace candela
