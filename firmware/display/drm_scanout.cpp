#include "display/drm_scanout.h"

#include <drm_fourcc.h>
#include <xf86drm.h>
#include <xf86drmMode.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/log.h"

namespace candela {
namespace {
// The DRM framebuffer made for a GBM buffer, removed when GBM frees the buffer.
struct BufferFb {
  int fd;
  uint32_t fb_id;
  static void destroy(gbm_bo*, void* data) {
    auto* self = static_cast<BufferFb*>(data);
    drmModeRmFB(self->fd, self->fb_id);
    delete self;
  }
};
}  // namespace

DrmScanout::DrmScanout(const KmsOutput& out) : out_(out) {
  gbm_ = gbm_create_device(out_.fd);
  if (!gbm_) throw RuntimeError("drm: gbm_create_device failed on " + out_.device);
  try {
    if (!egl_has_extension(EGL_NO_DISPLAY, "EGL_KHR_platform_gbm") &&
        !egl_has_extension(EGL_NO_DISPLAY, "EGL_MESA_platform_gbm"))
      throw RuntimeError("drm: EGL has no GBM platform (install libegl-mesa0)");
    auto get_platform_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
        eglGetProcAddress("eglGetPlatformDisplayEXT"));
    if (!get_platform_display) throw RuntimeError("drm: no eglGetPlatformDisplayEXT");
    egl_.emplace(get_platform_display(EGL_PLATFORM_GBM_KHR, gbm_, nullptr), EGL_WINDOW_BIT,
                 static_cast<EGLint>(kFormat));
  } catch (...) {
    gbm_device_destroy(gbm_);
    throw;
  }
}

DrmScanout::~DrmScanout() {
  if (egl_) eglMakeCurrent(egl_->display(), EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  destroy_surfaces(false);
  egl_.reset();
  gbm_device_destroy(gbm_);
}

void DrmScanout::create_surfaces(int w, int h) {
  const uint32_t width = static_cast<uint32_t>(w), height = static_cast<uint32_t>(h);
  // Modifiers both the plane scans out and EGL renders to.
  std::vector<uint64_t> mods = out_.modifiers;
  mods.erase(std::remove(mods.begin(), mods.end(), DRM_FORMAT_MOD_INVALID), mods.end());
  if (!mods.empty() &&
      egl_has_extension(egl_->display(), "EGL_EXT_image_dma_buf_import_modifiers")) {
    auto query = reinterpret_cast<PFNEGLQUERYDMABUFMODIFIERSEXTPROC>(
        eglGetProcAddress("eglQueryDmaBufModifiersEXT"));
    EGLint n = 0;
    if (query && query(egl_->display(), kFormat, 0, nullptr, nullptr, &n) && n > 0) {
      std::vector<EGLuint64KHR> egl_mods(static_cast<size_t>(n));
      std::vector<EGLBoolean> external(static_cast<size_t>(n));
      query(egl_->display(), kFormat, n, egl_mods.data(), external.data(), &n);
      std::vector<uint64_t> common;
      for (uint64_t m : mods)
        for (EGLint i = 0; i < n; ++i)
          if (egl_mods[static_cast<size_t>(i)] == m && !external[static_cast<size_t>(i)])
            common.push_back(m);
      LOG_INFO("drm: plane offers %zu modifiers for XRGB8888, EGL %d, %zu in common", mods.size(),
               n, common.size());
      mods = std::move(common);
    }
  }
  if (!mods.empty()) {
    surface_ = gbm_surface_create_with_modifiers(gbm_, width, height, kFormat, mods.data(),
                                                 static_cast<unsigned>(mods.size()));
    if (!surface_)
      LOG_INFO(
          "drm: GBM cannot allocate with the plane's modifiers (%s): falling back to an "
          "implicit scan-out buffer",
          std::strerror(errno));
  } else {
    LOG_INFO("drm: no modifier list to negotiate: letting GBM pick a scan-out buffer");
  }
  if (!surface_)
    surface_ =
        gbm_surface_create(gbm_, width, height, kFormat, GBM_BO_USE_SCANOUT | GBM_BO_USE_RENDERING);
  if (!surface_)
    throw RuntimeError("drm: cannot create a " + std::to_string(w) + "x" + std::to_string(h) +
                       " GBM scan-out surface: " + std::strerror(errno));

  auto create_surface = reinterpret_cast<PFNEGLCREATEPLATFORMWINDOWSURFACEEXTPROC>(
      eglGetProcAddress("eglCreatePlatformWindowSurfaceEXT"));
  egl_surface_ = create_surface ? create_surface(egl_->display(), egl_->config(), surface_, nullptr)
                                : eglCreateWindowSurface(
                                      egl_->display(), egl_->config(),
                                      reinterpret_cast<EGLNativeWindowType>(surface_), nullptr);
  if (egl_surface_ == EGL_NO_SURFACE)
    throw RuntimeError("drm: cannot create an EGL surface on GBM: " +
                       egl_error_string(eglGetError()));
  egl_->make_current(egl_surface_);
}

void DrmScanout::destroy_surfaces(bool keep_context) {
  if (egl_ && egl_surface_ != EGL_NO_SURFACE) {
    eglMakeCurrent(egl_->display(), EGL_NO_SURFACE, EGL_NO_SURFACE,
                   keep_context ? egl_->context() : EGL_NO_CONTEXT);
    eglDestroySurface(egl_->display(), egl_surface_);
    egl_surface_ = EGL_NO_SURFACE;
  }
  if (surface_) {
    gbm_surface_destroy(surface_);  // removes the framebuffers (BufferFb::destroy)
    surface_ = nullptr;
  }
}

gbm_bo* DrmScanout::swap() {
  if (!eglSwapBuffers(egl_->display(), egl_surface_))
    throw RuntimeError("drm: eglSwapBuffers failed: " + egl_error_string(eglGetError()));
  gbm_bo* bo = gbm_surface_lock_front_buffer(surface_);
  if (!bo) throw RuntimeError("drm: gbm_surface_lock_front_buffer failed");
  return bo;
}

uint32_t DrmScanout::framebuffer_for(gbm_bo* bo) {
  if (auto* known = static_cast<BufferFb*>(gbm_bo_get_user_data(bo))) return known->fb_id;
  const uint32_t w = gbm_bo_get_width(bo), h = gbm_bo_get_height(bo);
  const uint32_t format = gbm_bo_get_format(bo);
  const uint64_t modifier = gbm_bo_get_modifier(bo);
  const int planes = std::min(gbm_bo_get_plane_count(bo), 4);
  uint32_t handles[4] = {}, strides[4] = {}, offsets[4] = {};
  uint64_t modifiers[4] = {};
  for (int i = 0; i < planes; ++i) {
    handles[i] = gbm_bo_get_handle_for_plane(bo, i).u32;
    strides[i] = gbm_bo_get_stride_for_plane(bo, i);
    offsets[i] = gbm_bo_get_offset(bo, i);
    modifiers[i] = modifier;
  }
  uint32_t fb = 0;
  // An explicit modifier only when there is one: LINEAR or INVALID go
  // without, which every driver takes (vkms rejects an invalid modifier).
  if (modifier != DRM_FORMAT_MOD_INVALID && modifier != DRM_FORMAT_MOD_LINEAR &&
      out_.addfb2_modifiers) {
    if (drmModeAddFB2WithModifiers(out_.fd, w, h, format, handles, strides, offsets, modifiers, &fb,
                                   DRM_MODE_FB_MODIFIERS) != 0) {
      LOG_WARN("drm: AddFB2 with modifier 0x%llx failed (%s): trying without",
               static_cast<unsigned long long>(modifier), std::strerror(errno));
      fb = 0;
    }
  } else if (!logged_plain_fb_) {
    logged_plain_fb_ = true;
    LOG_INFO("drm: buffer modifier is %s: adding framebuffers without modifiers",
             modifier == DRM_FORMAT_MOD_INVALID ? "INVALID" : "LINEAR");
  }
  if (!fb && drmModeAddFB2(out_.fd, w, h, format, handles, strides, offsets, &fb, 0) != 0) {
    LOG_ERROR("drm: drmModeAddFB2 %ux%u failed: %s", w, h, std::strerror(errno));
    return 0;
  }
  gbm_bo_set_user_data(bo, new BufferFb{out_.fd, fb}, &BufferFb::destroy);
  return fb;
}

}  // namespace candela
