// Headless: EGL on Mesa's surfaceless platform, drawing into an offscreen
// framebuffer. Used by tests, CI and frame dumps (PNG folder, .y4m, .mp4).
#include <memory>
#include <optional>

#include "core/error.h"
#include "core/log.h"
#include "display/display.h"
#include "display/egl_context.h"
#include "display/frame_writer.h"
#include "gl/gles.h"
#include "gl/texture.h"

namespace candela {
namespace {

class HeadlessDisplay final : public Display {
 public:
  explicit HeadlessDisplay(const DisplayOptions& o)
      : width_(o.width > 0 ? o.width : 1280), height_(o.height > 0 ? o.height : 720) {
    if (!egl_has_extension(EGL_NO_DISPLAY, "EGL_MESA_platform_surfaceless"))
      throw RuntimeError(
          "headless: EGL has no EGL_MESA_platform_surfaceless (install libegl-mesa0)");
    auto get_platform_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
        eglGetProcAddress("eglGetPlatformDisplayEXT"));
    if (!get_platform_display) throw RuntimeError("headless: no eglGetPlatformDisplayEXT");
    egl_.emplace(get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr),
                 EGL_PBUFFER_BIT);
    egl_->make_current(EGL_NO_SURFACE);

    fbo_ = make_framebuffer();
    color_ = make_renderbuffer();
    depth_ = make_renderbuffer();
    glBindRenderbuffer(GL_RENDERBUFFER, color_.get());
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width_, height_);
    glBindRenderbuffer(GL_RENDERBUFFER, depth_.get());
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH24_STENCIL8, width_, height_);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo_.get());
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, color_.get());
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER,
                              depth_.get());
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw RuntimeError("headless: offscreen framebuffer incomplete");
    if (!o.out_path.empty()) {
      writer_ = std::make_unique<AsyncFrameWriter>(
          open_frame_sink(o.out_path, width_, height_, o.fps, o.sound_path), width_, height_);
      LOG_INFO("headless: %dx%d, writing frames to %s", width_, height_, o.out_path.c_str());
    } else {
      LOG_INFO("headless: %dx%d, not writing frames", width_, height_);
    }
  }
  ~HeadlessDisplay() override {
    writer_.reset();
    fbo_.reset();
    color_.reset();
    depth_.reset();
  }

  std::string_view name() const override { return "headless"; }
  int width() const override { return width_; }
  int height() const override { return height_; }
  bool paced_by_vsync() const override { return false; }
  void begin_frame() override {
    glBindFramebuffer(GL_FRAMEBUFFER, fbo_.get());
    glViewport(0, 0, width_, height_);
  }
  void present() override {
    if (writer_) {
      uint8_t* slot = writer_->acquire();
      glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo_.get());
      glPixelStorei(GL_PACK_ALIGNMENT, 1);
      glReadPixels(0, 0, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, slot);
      writer_->submit();
    } else {
      glFinish();  // so frame times measure the GPU's work, as a real present would
    }
  }
  bool poll_events(DisplayEvents&) override { return true; }
  void finish() override {
    if (writer_) writer_->finish();
  }

 private:
  int width_, height_;
  std::optional<EglContext> egl_;
  Framebuffer fbo_;
  Renderbuffer color_, depth_;
  std::unique_ptr<AsyncFrameWriter> writer_;
};

}  // namespace

std::unique_ptr<Display> open_headless_display(const DisplayOptions& options) {
  return std::make_unique<HeadlessDisplay>(options);
}

}  // namespace candela
