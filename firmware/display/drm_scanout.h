// What the DRM display draws into and scans out: a GBM device and a surface
// of the mode's size (with a modifier both the plane and EGL take, where
// they say), the EGL context and window surface on it, and a DRM
// framebuffer for each GBM buffer (made once; GBM reuses a few).
#pragma once

#include <gbm.h>

#include <cstdint>
#include <optional>

#include "display/drm_kms.h"
#include "display/egl_context.h"

namespace candela {

class DrmScanout {
 public:
  static constexpr uint32_t kFormat = GBM_FORMAT_XRGB8888;  // == DRM_FORMAT_XRGB8888

  // The GBM device and EGL context on out's card (throws RuntimeError).
  explicit DrmScanout(const KmsOutput& out);
  ~DrmScanout();
  DrmScanout(const DrmScanout&) = delete;
  DrmScanout& operator=(const DrmScanout&) = delete;

  // Surfaces of w x h, the context current on them.
  void create_surfaces(int w, int h);
  // The surfaces gone (buffers still locked must be released first); the
  // context stays current without one (keep_context) so GL objects live on.
  void destroy_surfaces(bool keep_context = true);
  bool has_surfaces() const { return surface_ != nullptr; }
  // No surface yet (no screen): scenes build their GL objects meanwhile.
  void make_current_without_surface() { egl_->make_current(EGL_NO_SURFACE); }

  // The frame drawn: swapped and its buffer locked for scan-out (throws).
  gbm_bo* swap();
  // The DRM framebuffer of a locked buffer (0: none could be made, logged).
  uint32_t framebuffer_for(gbm_bo* bo);
  // A buffer off the screen, back to GBM.
  void release(gbm_bo* bo) { gbm_surface_release_buffer(surface_, bo); }

 private:
  const KmsOutput& out_;
  gbm_device* gbm_ = nullptr;
  gbm_surface* surface_ = nullptr;
  std::optional<EglContext> egl_;
  EGLSurface egl_surface_ = EGL_NO_SURFACE;
  bool logged_plain_fb_ = false;
};

}  // namespace candela
