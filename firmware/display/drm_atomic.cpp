// The DRM display's atomic path: one request per modeset, flip or switch-off.
#include <xf86drm.h>

#include "core/log.h"
#include "display/drm_commit.h"
#include "display/drm_mode.h"

namespace candela {

int AtomicRequest::commit(int fd, uint32_t flags, void* user_data) {
  drm_mode_atomic a{};
  a.flags = flags;
  a.count_objs = objects_;
  a.objs_ptr = reinterpret_cast<uintptr_t>(object_ids_);
  a.count_props_ptr = reinterpret_cast<uintptr_t>(counts_);
  a.props_ptr = reinterpret_cast<uintptr_t>(prop_ids_);
  a.prop_values_ptr = reinterpret_cast<uintptr_t>(values_);
  a.user_data = reinterpret_cast<uintptr_t>(user_data);
  return drmIoctl(fd, DRM_IOCTL_MODE_ATOMIC, &a);
}

void DrmCommit::add_plane_properties(uint32_t fb, int w, int h) {
  const KmsPropertyIds& p = out_.props;
  const uint32_t plane = out_.plane_id;
  const uint64_t pw = static_cast<uint64_t>(w), ph = static_cast<uint64_t>(h);
  req_.add(plane, p.plane_fb_id, fb);
  req_.add(plane, p.plane_crtc_id, out_.crtc_id);
  req_.add(plane, p.plane_src_x, 0);
  req_.add(plane, p.plane_src_y, 0);
  req_.add(plane, p.plane_src_w, pw << 16);
  req_.add(plane, p.plane_src_h, ph << 16);
  req_.add(plane, p.plane_crtc_x, 0);
  req_.add(plane, p.plane_crtc_y, 0);
  req_.add(plane, p.plane_crtc_w, pw);
  req_.add(plane, p.plane_crtc_h, ph);
}

bool DrmCommit::atomic_modeset(uint32_t fb, int w, int h) {
  const KmsPropertyIds& p = out_.props;
  req_.clear();
  req_.add(out_.connector_id, p.connector_crtc_id, out_.crtc_id);
  req_.add(out_.crtc_id, p.crtc_mode_id, mode_blob_);
  req_.add(out_.crtc_id, p.crtc_active, 1);
  add_plane_properties(fb, w, h);
  // Blocking and without an event: the next present() flips onto it.
  if (req_.commit(out_.fd, DRM_MODE_ATOMIC_ALLOW_MODESET, nullptr) != 0) return false;
  ++modesets_;
  LOG_INFO("drm: atomic modeset %s on %s done", describe_mode(out_.mode).c_str(),
           out_.connector_name.c_str());
  return true;
}

bool DrmCommit::atomic_flip(uint32_t fb, int w, int h, void* user_data) {
  req_.clear();
  add_plane_properties(fb, w, h);
  return req_.commit(out_.fd, DRM_MODE_ATOMIC_NONBLOCK | DRM_MODE_PAGE_FLIP_EVENT, user_data) == 0;
}

bool DrmCommit::atomic_crtc_off() {
  if (!out_.atomic) return false;
  const KmsPropertyIds& p = out_.props;
  req_.clear();
  req_.add(out_.crtc_id, p.crtc_active, 0);
  req_.add(out_.plane_id, p.plane_fb_id, 0);
  req_.add(out_.plane_id, p.plane_crtc_id, 0);
  return req_.commit(out_.fd, DRM_MODE_ATOMIC_ALLOW_MODESET, nullptr) == 0;
}

}  // namespace candela
