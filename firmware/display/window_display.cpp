// The desktop emulator: an X11 window (also works under XWayland) with an EGL
// window surface. Esc/q quit; arrows, space and o are passed on as wind keys.
// Every X event also goes to DisplayEvents::on_x11_event first (the studio's
// UI); the window's size follows ConfigureNotify (resizing).
#include <memory>
#include <optional>

#include "core/error.h"
#include "core/log.h"
#include "display/display.h"
#include "display/egl_context.h"
#include "gl/gles.h"

#ifdef CANDELA_HAVE_X11
#include <X11/Xlib.h>
#include <X11/Xutil.h>
#include <X11/keysym.h>
#endif

namespace candela {

#ifdef CANDELA_HAVE_X11
namespace {

class WindowDisplay final : public Display {
 public:
  explicit WindowDisplay(const DisplayOptions& o)
      : width_(o.width > 0 ? o.width : 1280), height_(o.height > 0 ? o.height : 720) {
    x_ = XOpenDisplay(nullptr);
    if (!x_) throw RuntimeError("window: cannot open X display (is DISPLAY set?)");
    const int screen = DefaultScreen(x_);
    XSetWindowAttributes attrs{};
    attrs.event_mask = KeyPressMask | KeyReleaseMask | ButtonPressMask | ButtonReleaseMask |
                       PointerMotionMask | LeaveWindowMask | FocusChangeMask | StructureNotifyMask |
                       ExposureMask;
    attrs.background_pixel = BlackPixel(x_, screen);
    win_ = XCreateWindow(x_, RootWindow(x_, screen), 0, 0, width_, height_, 0, CopyFromParent,
                         InputOutput, CopyFromParent, CWEventMask | CWBackPixel, &attrs);
    XStoreName(x_, win_, o.title.c_str());
    wm_delete_ = XInternAtom(x_, "WM_DELETE_WINDOW", False);
    XSetWMProtocols(x_, win_, &wm_delete_, 1);
    XMapWindow(x_, win_);
    XFlush(x_);

    auto get_platform_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
        eglGetProcAddress("eglGetPlatformDisplayEXT"));
    EGLDisplay dpy = get_platform_display
                         ? get_platform_display(EGL_PLATFORM_X11_KHR, x_, nullptr)
                         : eglGetDisplay(reinterpret_cast<EGLNativeDisplayType>(x_));
    egl_.emplace(dpy, EGL_WINDOW_BIT);
    surface_ = eglCreateWindowSurface(egl_->display(), egl_->config(),
                                      static_cast<EGLNativeWindowType>(win_), nullptr);
    if (surface_ == EGL_NO_SURFACE)
      throw RuntimeError("window: cannot create EGL window surface: " +
                         egl_error_string(eglGetError()));
    egl_->make_current(surface_);
    vsync_ = o.vsync && eglSwapInterval(egl_->display(), 1);
    LOG_INFO("window: %dx%d%s", width_, height_, vsync_ ? ", vsync" : "");
  }
  ~WindowDisplay() override {
    if (egl_ && surface_ != EGL_NO_SURFACE) {
      eglMakeCurrent(egl_->display(), EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
      eglDestroySurface(egl_->display(), surface_);
    }
    egl_.reset();
    if (win_) XDestroyWindow(x_, win_);
    if (x_) XCloseDisplay(x_);
  }

  std::string_view name() const override { return "window"; }
  int width() const override { return width_; }
  int height() const override { return height_; }
  bool paced_by_vsync() const override { return vsync_; }
  void begin_frame() override {
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, width_, height_);
  }
  void present() override { eglSwapBuffers(egl_->display(), surface_); }
  bool poll_events(DisplayEvents& events) override {
    while (XPending(x_)) {
      XEvent ev;
      XNextEvent(x_, &ev);
      if (ev.type == ClientMessage && static_cast<Atom>(ev.xclient.data.l[0]) == wm_delete_)
        return false;
      if (ev.type == ConfigureNotify) {
        width_ = ev.xconfigure.width;
        height_ = ev.xconfigure.height;
      }
      if (events.on_x11_event(ev)) continue;
      if (ev.type == KeyPress) {
        switch (XLookupKeysym(&ev.xkey, 0)) {
          case XK_Escape:
          case XK_q:
            return false;
          case XK_Left:
            events.on_key(Key::kLeft);
            break;
          case XK_Right:
            events.on_key(Key::kRight);
            break;
          case XK_Up:
            events.on_key(Key::kUp);
            break;
          case XK_Down:
            events.on_key(Key::kDown);
            break;
          case XK_space:
            events.on_key(Key::kSpace);
            break;
          case XK_o:
            events.on_key(Key::kBlowOut);
            break;
          default:
            events.on_key(Key::kOther);
            break;
        }
      }
    }
    return true;
  }

 private:
  int width_, height_;
  ::Display* x_ = nullptr;
  Window win_ = 0;
  Atom wm_delete_ = 0;
  std::optional<EglContext> egl_;
  EGLSurface surface_ = EGL_NO_SURFACE;
  bool vsync_ = false;
};

}  // namespace

std::unique_ptr<Display> open_window_display(const DisplayOptions& options) {
  return std::make_unique<WindowDisplay>(options);
}
#else
std::unique_ptr<Display> open_window_display(const DisplayOptions&) {
  throw RuntimeError("window: built without X11 (install libx11-dev and rebuild)");
}
#endif

}  // namespace candela
