// EGL set-up shared by every backend: pick a config, make a GLES 3 context.
#pragma once

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <string>

namespace candela {

std::string egl_error_string(EGLint error);
bool egl_has_extension(EGLDisplay dpy, const char* name);  // dpy may be EGL_NO_DISPLAY (client)

class EglContext {
 public:
  // Takes ownership of an already obtained display: initialises it, picks an
  // RGBA8888 config for `surface_type` (0 for surfaceless) with a depth buffer
  // of at least 16 bits where the driver has one, optionally with the given
  // native visual id (the GBM format on DRM), and creates a GLES 3 context.
  EglContext(EGLDisplay display, EGLint surface_type, EGLint native_visual_id = 0);
  ~EglContext();
  EglContext(const EglContext&) = delete;
  EglContext& operator=(const EglContext&) = delete;

  EGLDisplay display() const { return display_; }
  EGLConfig config() const { return config_; }
  EGLContext context() const { return context_; }
  void make_current(EGLSurface surface) const;

 private:
  EGLDisplay display_ = EGL_NO_DISPLAY;
  EGLConfig config_ = nullptr;
  EGLContext context_ = EGL_NO_CONTEXT;
};

}  // namespace candela
