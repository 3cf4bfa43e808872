// The kiosk: DRM/KMS + GBM + EGL. Renders into a GBM surface and shows
// each frame with a page flip (atomic, or legacy where atomic is missing),
// paced by the display's vertical blank. Restores the CRTC it found on exit.
#include <xf86drm.h>
#include <xf86drmMode.h>

#include <cerrno>
#include <cstring>
#include <string>

#include "core/error.h"
#include "core/log.h"
#include "display/display.h"
#include "display/drm_commit.h"
#include "display/drm_flips.h"
#include "display/drm_mode.h"
#include "display/drm_hotplug.h"
#include "display/drm_kms.h"
#include "display/drm_master.h"
#include "display/drm_scanout.h"
#include "gl/gles.h"

namespace candela {
namespace {

constexpr uint32_t kFormat = DrmScanout::kFormat;

std::string errno_string(int e) { return std::strerror(e); }

class DrmDisplay final : public Display {
 public:
  // With --display drm (not auto) a card with nothing connected is taken
  // as it is: the kiosk waits for a screen (hot-plug) instead of exiting.
  explicit DrmDisplay(const DisplayOptions& options)
      : options_(options),
        out_(open_kms_output(options, kFormat, options.kind == "drm")),
        hotplug_(out_.fd, out_.device),
        scanout_(out_),
        commit_(out_),
        master_(out_),
        flips_(out_, scanout_) {
    screen_ = out_.connector_id != 0;
    if (!options.vsync) LOG_INFO("drm: vsync cannot be turned off on KMS; flips stay vblank-paced");
    if (screen_) {
      take_mode(false);
    } else {
      scanout_.make_current_without_surface();  // scenes build their GL objects meanwhile
      LOG_WARN(
          "drm: no screen is connected to %s: waiting for one (drawing starts when a "
          "monitor is connected or switched on)",
          out_.device.c_str());
    }
  }

  ~DrmDisplay() override {
    try {
      flips_.wait();
    } catch (const std::exception& e) {
      LOG_WARN("%s", e.what());
    }
    if (presented_ > 0 && screen_) {  // else never touched the display, or it is gone
      if (master_.lost())
        LOG_INFO("drm: another program holds the display: leaving CRTC %u as it is", out_.crtc_id);
      else
        commit_.restore_crtc();
    }
    const uint64_t modesets = commit_.modesets();
    if (presented_ > 0)
      LOG_INFO(
          "drm: presented %llu frames (%llu modeset%s + %llu page flips completed), %lld vblanks "
          "missed%s",
          static_cast<unsigned long long>(presented_), static_cast<unsigned long long>(modesets),
          modesets == 1 ? "" : "s", static_cast<unsigned long long>(flips_.done()),
          static_cast<long long>(flips_.missed()),
          master_.times_lost()
              ? (", " + std::to_string(master_.times_lost()) + " times without DRM master").c_str()
              : "");
    flips_.release_all();
  }

  std::string_view name() const override { return "drm"; }
  int width() const override { return width_; }
  int height() const override { return height_; }
  bool paced_by_vsync() const override { return true; }
  int64_t missed_vblanks() const override { return flips_.missed(); }

  void begin_frame() override {
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, width_, height_);
  }

  void present() override {
    if (!screen_) return;  // the frame loop waits in wait_for_screen() meanwhile
    gbm_bo* bo = scanout_.swap();
    const uint32_t fb = scanout_.framebuffer_for(bo);
    if (!fb) {
      scanout_.release(bo);
      throw RuntimeError("drm: cannot make a framebuffer for a GBM buffer");
    }
    if (master_.lost()) {
      if (!master_.try_resume(commit_, fb, width_, height_)) {
        scanout_.release(bo);  // not shown
        master_.wait_for_retry();
        return;
      }
      flips_.shown(bo);
      needs_modeset_ = false;
    } else if (presented_ == 0 || needs_modeset_) {
      // First frame, or the screen back on after set_screen_power(false):
      // the old front buffer is off the screen and goes back to GBM.
      if (!commit_.modeset(fb, width_, height_)) {
        const int e = errno;
        scanout_.release(bo);
        master_.lose(e);
        return;
      }
      flips_.shown(bo);
      needs_modeset_ = false;
    } else {
      // One flip in flight at a time: committing while one is pending gives
      // EBUSY. Waiting here, not after the commit, lets the next frame render
      // while this one waits for its vblank.
      if (!flips_.wait() || !commit_.queue_flip(fb, width_, height_, &flips_)) {
        const int e = errno;
        scanout_.release(bo);
        master_.lose(e);
        return;
      }
      flips_.queued(bo);
    }
    ++presented_;
  }

  // A hot-plug uevent, looked for without blocking (one poll() per frame).
  bool poll_events(DisplayEvents&) override {
    follow_hotplug(0);
    return true;
  }

  bool screen_present() const override { return screen_; }

  bool wait_for_screen(int timeout_ms) override {
    if (!screen_) follow_hotplug(timeout_ms);
    return screen_;
  }

  // Off: the flip in flight completes, then the CRTC goes inactive with the
  // plane detached (atomic) or the connector's DPMS goes Off (legacy); the
  // monitor sees no signal and sleeps. On: the next present() sets the mode
  // again (atomic) or DPMS On and flips as before (legacy).
  bool set_screen_power(bool on) override {
    if (on == screen_on_) return true;
    if (!screen_) {  // nothing connected: the mode is set when a screen is
      screen_on_ = on;
      return true;
    }
    try {
      flips_.wait();
    } catch (const std::exception& e) {
      LOG_WARN("%s", e.what());
    }
    if (presented_ == 0) {  // nothing shown yet: the first present() sets the mode
      screen_on_ = on;
      return true;
    }
    bool done = false;
    if (out_.atomic) {
      if (!on) {
        done = commit_.atomic_crtc_off();
        if (!done)
          LOG_WARN("drm: switching the CRTC off failed (%s); trying DPMS",
                   errno_string(errno).c_str());
      } else {
        done = true;  // present() modesets (ACTIVE=1) with the next frame
      }
      if (done) needs_modeset_ = !on ? true : needs_modeset_;
    }
    if (!done) done = commit_.set_dpms(on);
    if (done) {
      screen_on_ = on;
      flips_.resync();
      LOG_INFO("drm: screen %s (%s)", on ? "on" : "off",
               out_.atomic ? "CRTC ACTIVE" : "connector DPMS");
    }
    return done;
  }

  void finish() override { flips_.wait(); }

 private:
  // --- Connector hot-plug (drm_hotplug.h) ---------------------------------
  // A change of the card makes the connectors be looked at again: a screen
  // that appears is driven with the mode chosen again, one that goes away
  // pauses drawing (CRTC off).
  void follow_hotplug(int timeout_ms) {
    if (hotplug_.changed(timeout_ms, screen_)) reprobe();
  }

  void reprobe() {
    const bool had_screen = screen_;
    const uint32_t old_connector = out_.connector_id;
    const drmModeModeInfo old_mode = out_.mode;
    std::string why;
    if (screen_) {
      // Ours first: still connected with the same mode is nothing to do.
      drmModeConnector* c = drmModeGetConnector(out_.fd, out_.connector_id);
      const bool connected = c && c->connection == DRM_MODE_CONNECTED && c->count_modes > 0;
      drmModeFreeConnector(c);
      if (!connected) {
        screen_gone();
        why = "nothing connected";
      }
    }
    if (!probe_kms_connector(out_, options_, kFormat, why)) {
      if (!had_screen)
        LOG_INFO("drm: a hot-plug event on %s: still %s", out_.device.c_str(), why.c_str());
      return;
    }
    if (!needs_new_mode(screen_, old_connector, old_mode, out_.connector_id, out_.mode)) return;
    if (screen_) screen_gone();  // another connector or mode: set up afresh
    take_mode(true);
  }

  // The CRTC off (nothing to show it on); the next screen is set up afresh.
  void screen_gone() {
    try {
      flips_.wait();
    } catch (const std::exception& e) {
      LOG_WARN("%s", e.what());
    }
    if (!master_.lost() && !commit_.atomic_crtc_off()) commit_.legacy_crtc_off();
    screen_ = false;
    ++screens_lost_;
    LOG_WARN("drm: the screen on %s went away: drawing paused until a screen is connected",
             out_.connector_name.c_str());
  }

  // out_ holds a connected connector and its mode: surfaces of that size
  // (made again when the size changed), the mode blob; the next present()
  // sets the mode.
  void take_mode(bool hotplugged) {
    const int w = out_.mode.hdisplay, h = out_.mode.vdisplay;
    if (scanout_.has_surfaces() && (w != width_ || h != height_)) {
      flips_.release_all();
      scanout_.destroy_surfaces();
    }
    width_ = w;
    height_ = h;
    commit_.take_mode();
    if (!scanout_.has_surfaces()) scanout_.create_surfaces(w, h);
    if (hotplugged)
      LOG_INFO("drm: a screen on %s: mode %s; drawing on it", out_.connector_name.c_str(),
               describe_mode(out_.mode).c_str());
    needs_modeset_ = true;
    flips_.resync();
    screen_ = true;
  }

  DisplayOptions options_;  // the mode is chosen again by them on hot-plug
  KmsOutput out_;           // closes the card and drops master last
  DrmHotplug hotplug_;
  DrmScanout scanout_;
  DrmCommit commit_;
  DrmMaster master_;
  DrmFlips flips_;
  int width_ = 0, height_ = 0;
  bool screen_on_ = true;
  bool needs_modeset_ = false;  // the CRTC was switched off: the next present() modesets
  uint64_t presented_ = 0;
  bool screen_ = false;  // a connected connector with its mode set up
  uint64_t screens_lost_ = 0;
};

}  // namespace

std::unique_ptr<Display> open_drm_display(const DisplayOptions& options) {
  return std::make_unique<DrmDisplay>(options);
}

}  // namespace candela
