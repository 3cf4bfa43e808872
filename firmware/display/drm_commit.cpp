#include "display/drm_commit.h"
#include "display/drm_mode.h"

#include <cerrno>
#include <cstring>
#include <string>

#include "core/log.h"

namespace candela {

bool is_master_error(int e) { return e == EACCES || e == EPERM || e == EBUSY; }

DrmCommit::~DrmCommit() {
  if (mode_blob_) drmModeDestroyPropertyBlob(out_.fd, mode_blob_);
  if (saved_crtc_) drmModeFreeCrtc(saved_crtc_);
}

void DrmCommit::take_mode() {
  if (!saved_crtc_) saved_crtc_ = drmModeGetCrtc(out_.fd, out_.crtc_id);
  if (mode_blob_) drmModeDestroyPropertyBlob(out_.fd, mode_blob_);
  mode_blob_ = 0;
  if (out_.atomic &&
      drmModeCreatePropertyBlob(out_.fd, &out_.mode, sizeof out_.mode, &mode_blob_) != 0) {
    LOG_WARN("drm: cannot create a mode blob (%s): falling back to legacy modesetting",
             std::strerror(errno));
    out_.atomic = false;
  }
}

bool DrmCommit::modeset(uint32_t fb, int w, int h) {
  if (out_.atomic) {
    if (atomic_modeset(fb, w, h)) return true;
    if (is_master_error(errno)) return false;
    LOG_WARN("drm: atomic modeset failed (%s): falling back to legacy modesetting",
             std::strerror(errno));
    out_.atomic = false;
  }
  return legacy_modeset(fb);
}

bool DrmCommit::queue_flip(uint32_t fb, int w, int h, void* user_data) {
  if (out_.atomic) {
    if (atomic_flip(fb, w, h, user_data)) return true;
    if (is_master_error(errno)) return false;
    LOG_WARN("drm: atomic page flip failed (%s): falling back to legacy page flips",
             std::strerror(errno));
    out_.atomic = false;
  }
  return legacy_flip(fb, user_data);
}

void DrmCommit::restore_crtc() {
  int rc;
  std::string what;
  if (saved_crtc_ && saved_crtc_->mode_valid && saved_crtc_->buffer_id) {
    uint32_t connector = out_.connector_id;
    rc = drmModeSetCrtc(out_.fd, saved_crtc_->crtc_id, saved_crtc_->buffer_id, saved_crtc_->x,
                        saved_crtc_->y, &connector, 1, &saved_crtc_->mode);
    what = describe_mode(saved_crtc_->mode) + ", framebuffer " +
           std::to_string(saved_crtc_->buffer_id);
  } else {
    rc = drmModeSetCrtc(out_.fd, out_.crtc_id, 0, 0, 0, nullptr, 0, nullptr);
    what = "off";
  }
  if (rc == 0)
    LOG_INFO("drm: restored CRTC %u to its previous state (%s)", out_.crtc_id, what.c_str());
  else
    LOG_WARN("drm: could not restore CRTC %u to its previous state (%s): %s", out_.crtc_id,
             what.c_str(), std::strerror(errno));
}

}  // namespace candela
