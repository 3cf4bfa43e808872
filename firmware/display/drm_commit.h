// How frames reach one KMS output (the DRM display's): the mode set, page
// flips, the CRTC switched off, DPMS, the CRTC found at start restored.
// Atomically (drm_atomic.cpp) where the driver has it, by the legacy calls
// (drm_legacy.cpp) otherwise; an atomic call the driver refuses falls back
// to legacy for good, with a log line. Calls that return false set errno:
// another program holds DRM master (is_master_error).
#pragma once

#include <xf86drmMode.h>

#include <cstdint>

#include "display/drm_atomic.h"
#include "display/drm_kms.h"

namespace candela {

// What the kernel answers a commit, flip or modeset from a client that is no
// longer DRM master (EACCES; EPERM from some drivers), or while another
// master's commit holds the CRTC (EBUSY).
bool is_master_error(int e);

class DrmCommit {
 public:
  explicit DrmCommit(KmsOutput& out) : out_(out) {}
  ~DrmCommit();
  DrmCommit(const DrmCommit&) = delete;
  DrmCommit& operator=(const DrmCommit&) = delete;

  // out.mode is the mode to drive now: the CRTC as found is kept (once) for
  // restore_crtc(), the atomic mode blob made again (none: legacy from now on).
  void take_mode();
  // The mode set, showing framebuffer fb (w x h). False: no master.
  bool modeset(uint32_t fb, int w, int h);
  // A flip to fb at the next vblank, its event to user_data. False: no master.
  bool queue_flip(uint32_t fb, int w, int h, void* user_data);
  // Atomic only: CRTC inactive, plane detached (the monitor sees no signal).
  // False: not atomic, or refused (errno set).
  bool atomic_crtc_off();
  // Legacy: the CRTC off, nothing shown.
  void legacy_crtc_off();
  // Legacy: the connector's DPMS property. False (logged): none, or refused.
  bool set_dpms(bool on);
  // The CRTC as it was before take_mode(), or off; logged either way.
  void restore_crtc();

  bool atomic() const { return out_.atomic; }
  uint64_t modesets() const { return modesets_; }

 private:
  // drm_atomic.cpp
  bool atomic_modeset(uint32_t fb, int w, int h);
  bool atomic_flip(uint32_t fb, int w, int h, void* user_data);
  void add_plane_properties(uint32_t fb, int w, int h);
  // drm_legacy.cpp
  bool legacy_modeset(uint32_t fb);
  bool legacy_flip(uint32_t fb, void* user_data);

  KmsOutput& out_;
  AtomicRequest req_;
  uint32_t mode_blob_ = 0;
  drmModeCrtc* saved_crtc_ = nullptr;
  uint64_t modesets_ = 0;
};

}  // namespace candela
