#include "display/egl_context.h"

#include <cstring>
#include <vector>

#include "core/error.h"
#include "core/log.h"
#include "gl/gles.h"

namespace candela {

#ifdef CANDELA_SANITIZE
void pin_gl_drivers();  // sanitizer_pins.cpp
#endif

std::string egl_error_string(EGLint e) {
  switch (e) {
#define C(x) \
  case x:    \
    return #x;
    C(EGL_SUCCESS)
    C(EGL_NOT_INITIALIZED)
        C(EGL_BAD_ACCESS) C(EGL_BAD_ALLOC) C(EGL_BAD_ATTRIBUTE) C(EGL_BAD_CONTEXT) C(EGL_BAD_CONFIG)
            C(EGL_BAD_CURRENT_SURFACE) C(EGL_BAD_DISPLAY) C(EGL_BAD_SURFACE) C(EGL_BAD_MATCH)
                C(EGL_BAD_PARAMETER) C(EGL_BAD_NATIVE_PIXMAP) C(EGL_BAD_NATIVE_WINDOW)
                    C(EGL_CONTEXT_LOST)
#undef C
                        default : return "EGL error " +
                                  std::to_string(e);
  }
}

bool egl_has_extension(EGLDisplay dpy, const char* name) {
  const char* exts = eglQueryString(dpy, EGL_EXTENSIONS);
  if (!exts) return false;
  const size_t n = std::strlen(name);
  for (const char* p = exts; (p = std::strstr(p, name)); p += n)
    if ((p == exts || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
  return false;
}

EglContext::EglContext(EGLDisplay display, EGLint surface_type, EGLint native_visual_id)
    : display_(display) {
  if (display_ == EGL_NO_DISPLAY) throw RuntimeError("EGL: no display");
  EGLint major = 0, minor = 0;
  if (!eglInitialize(display_, &major, &minor))
    throw RuntimeError("EGL: eglInitialize failed: " + egl_error_string(eglGetError()));
#ifdef CANDELA_SANITIZE
  pin_gl_drivers();
#endif
  if (!eglBindAPI(EGL_OPENGL_ES_API)) {
    eglTerminate(display_);
    throw RuntimeError("EGL: no OpenGL ES API");
  }
  // A depth buffer: the candles' bodies, the logs and the flames among them
  // are depth-tested where they are drawn at the screen's own size (a scene
  // drawn at a reduced size has its own, scene/scaled_render.h). EGL lists
  // the smallest depth and stencil first, so this asks for at least 16 bits
  // and gets the leanest such config; a driver without one still shows the
  // scene, in draw order, and says so.
  for (const EGLint depth : {16, 0}) {
    const EGLint attrs[] = {EGL_SURFACE_TYPE,
                            surface_type,
                            EGL_RED_SIZE,
                            8,
                            EGL_GREEN_SIZE,
                            8,
                            EGL_BLUE_SIZE,
                            8,
                            EGL_ALPHA_SIZE,
                            0,
                            EGL_DEPTH_SIZE,
                            depth,
                            EGL_RENDERABLE_TYPE,
                            EGL_OPENGL_ES3_BIT,
                            EGL_NONE};
    EGLint count = 0;
    eglChooseConfig(display_, attrs, nullptr, 0, &count);
    std::vector<EGLConfig> configs(static_cast<size_t>(count));
    if (count > 0) eglChooseConfig(display_, attrs, configs.data(), count, &count);
    for (EGLConfig c : configs) {
      EGLint id = 0;
      eglGetConfigAttrib(display_, c, EGL_NATIVE_VISUAL_ID, &id);
      if (native_visual_id == 0 || id == native_visual_id) {
        config_ = c;
        break;
      }
    }
    if (config_) {
      EGLint bits = 0, stencil = 0;
      eglGetConfigAttrib(display_, config_, EGL_DEPTH_SIZE, &bits);
      eglGetConfigAttrib(display_, config_, EGL_STENCIL_SIZE, &stencil);
      if (depth > 0)
        LOG_INFO("EGL: config with a %d-bit depth buffer (stencil %d bits)", bits, stencil);
      else
        LOG_WARN(
            "EGL: no config with a depth buffer%s: what is drawn at the screen's size "
            "overlaps in draw order",
            native_visual_id ? " matching the scan-out format" : "");
      break;
    }
  }
  if (!config_) {
    eglTerminate(display_);
    throw RuntimeError("EGL: no RGBA8888 GLES 3 config" +
                       std::string(native_visual_id ? " matching the scan-out format" : ""));
  }
  const EGLint ctx_attrs[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 0, EGL_NONE};
  context_ = eglCreateContext(display_, config_, EGL_NO_CONTEXT, ctx_attrs);
  if (context_ == EGL_NO_CONTEXT) {
    const EGLint e = eglGetError();
    eglTerminate(display_);
    throw RuntimeError("EGL: cannot create a GLES 3 context: " + egl_error_string(e));
  }
  LOG_INFO("EGL %d.%d, %s", major, minor, eglQueryString(display_, EGL_VENDOR));
}

void EglContext::make_current(EGLSurface surface) const {
  if (!eglMakeCurrent(display_, surface, surface, context_))
    throw RuntimeError("EGL: eglMakeCurrent failed: " + egl_error_string(eglGetError()));
  static bool logged = false;
  if (!logged) {
    logged = true;
    LOG_INFO("GL: %s, %s", reinterpret_cast<const char*>(glGetString(GL_RENDERER)),
             reinterpret_cast<const char*>(glGetString(GL_VERSION)));
  }
}

EglContext::~EglContext() {
  if (display_ != EGL_NO_DISPLAY) {
    eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (context_ != EGL_NO_CONTEXT) eglDestroyContext(display_, context_);
    eglTerminate(display_);
  }
}

}  // namespace candela
