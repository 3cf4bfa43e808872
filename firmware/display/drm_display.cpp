// The kiosk: DRM/KMS + GBM + EGL. Renders into a GBM surface and shows
// each frame with a page flip (atomic, or legacy where atomic is missing),
// paced by the display's vertical blank. Restores the CRTC it found on exit.
#include <drm_fourcc.h>
#include <gbm.h>
#include <libudev.h>
#include <poll.h>
#include <sys/stat.h>
#include <unistd.h>
#include <xf86drm.h>
#include <xf86drmMode.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <optional>
#include <thread>
#include <vector>

#include "core/error.h"
#include "core/log.h"
#include "display/display.h"
#include "display/drm_kms.h"
#include "display/egl_context.h"
#include "gl/gles.h"

namespace candela {
namespace {

constexpr uint32_t kFormat = GBM_FORMAT_XRGB8888;  // == DRM_FORMAT_XRGB8888
constexpr int kFlipTimeoutMs = 2000;
// Without DRM master (another program took the display) the frames are not
// shown; getting master back is retried after 50 ms, then less and less
// often, at most 500 ms apart (the frame loop runs at that rate meanwhile).
constexpr int kFirstRetryMs = 50, kMaxRetryMs = 500;
// Without a uevent monitor (no netlink socket allowed), the connectors are
// looked at this often while no screen is connected.
constexpr int kReprobeMs = 2000;

std::string errno_string(int e) { return std::strerror(e); }

// What the kernel answers a commit, flip or modeset from a client that is no
// longer DRM master (EACCES; EPERM from some drivers), or while another
// master's commit holds the CRTC (EBUSY).
bool is_master_error(int e) { return e == EACCES || e == EPERM || e == EBUSY; }

// An atomic request in fixed storage, committed with the ioctl itself:
// libdrm's drmModeAtomicCommit copies and sorts the request on the heap on
// every call, and a frame must not allocate. Properties of one object are
// added together (the kernel takes them grouped by object).
class AtomicRequest {
 public:
  void clear() {
    objects_ = 0;
    props_ = 0;
  }
  bool add(uint32_t object, uint32_t property, uint64_t value) {
    if (props_ == kMaxProps) return false;
    if (objects_ == 0 || object_ids_[objects_ - 1] != object) {
      if (objects_ == kMaxObjects) return false;
      object_ids_[objects_] = object;
      counts_[objects_++] = 0;
    }
    ++counts_[objects_ - 1];
    prop_ids_[props_] = property;
    values_[props_++] = value;
    return true;
  }
  // 0 or -1 with errno set, like libdrm.
  int commit(int fd, uint32_t flags, void* user_data) {
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

 private:
  static constexpr uint32_t kMaxObjects = 4, kMaxProps = 24;
  uint32_t objects_ = 0, props_ = 0;
  uint32_t object_ids_[kMaxObjects] = {}, counts_[kMaxObjects] = {};
  uint32_t prop_ids_[kMaxProps] = {};
  uint64_t values_[kMaxProps] = {};
};

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

class DrmDisplay final : public Display {
 public:
  // With --display drm (not auto) a card with nothing connected is taken
  // as it is: the kiosk waits for a screen (hot-plug) instead of exiting.
  explicit DrmDisplay(const DisplayOptions& options)
      : options_(options), out_(open_kms_output(options, kFormat, options.kind == "drm")) {
    screen_ = out_.connector_id != 0;
    if (!options.vsync) LOG_INFO("drm: vsync cannot be turned off on KMS; flips stay vblank-paced");
    try {
      open_hotplug_monitor();
      init_egl();
      if (screen_) {
        take_mode(false);
      } else {
        egl_->make_current(EGL_NO_SURFACE);  // scenes build their GL objects meanwhile
        LOG_WARN(
            "drm: no screen is connected to %s: waiting for one (drawing starts when a "
            "monitor is connected or switched on)",
            out_.device.c_str());
      }
    } catch (...) {
      release();
      close_hotplug_monitor();
      throw;
    }
    event_context_.version = 2;
    event_context_.page_flip_handler = &DrmDisplay::on_page_flip;
  }

  ~DrmDisplay() override {
    try {
      wait_for_flip();
    } catch (const std::exception& e) {
      LOG_WARN("%s", e.what());
    }
    restore_crtc();
    if (presented_ > 0)
      LOG_INFO(
          "drm: presented %llu frames (%llu modeset%s + %llu page flips completed), %lld vblanks "
          "missed%s",
          static_cast<unsigned long long>(presented_), static_cast<unsigned long long>(modesets_),
          modesets_ == 1 ? "" : "s", static_cast<unsigned long long>(flips_done_),
          static_cast<long long>(missed_),
          pauses_ ? (", " + std::to_string(pauses_) + " times without DRM master").c_str() : "");
    release();
    close_hotplug_monitor();
  }

  std::string_view name() const override { return "drm"; }
  int width() const override { return width_; }
  int height() const override { return height_; }
  bool paced_by_vsync() const override { return true; }
  int64_t missed_vblanks() const override { return missed_; }

  void begin_frame() override {
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, width_, height_);
  }

  void present() override {
    if (!screen_) return;  // the frame loop waits in wait_for_screen() meanwhile
    if (!eglSwapBuffers(egl_->display(), egl_surface_))
      throw RuntimeError("drm: eglSwapBuffers failed: " + egl_error_string(eglGetError()));
    gbm_bo* bo = gbm_surface_lock_front_buffer(surface_);
    if (!bo) throw RuntimeError("drm: gbm_surface_lock_front_buffer failed");
    const uint32_t fb = framebuffer_for(bo);
    if (!fb) {
      gbm_surface_release_buffer(surface_, bo);
      throw RuntimeError("drm: cannot make a framebuffer for a GBM buffer");
    }
    if (paused_) {
      if (!try_resume(fb)) {
        gbm_surface_release_buffer(surface_, bo);  // not shown
        wait_for_retry();
        return;
      }
      if (front_) gbm_surface_release_buffer(surface_, front_);
      front_ = bo;
      needs_modeset_ = false;
    } else if (presented_ == 0 || needs_modeset_) {
      // First frame, or the screen back on after set_screen_power(false):
      // the old front buffer is off the screen and goes back to GBM.
      if (!modeset(fb)) {
        const int e = errno;
        gbm_surface_release_buffer(surface_, bo);
        pause(e);
        return;
      }
      if (front_) gbm_surface_release_buffer(surface_, front_);
      front_ = bo;
      needs_modeset_ = false;
    } else {
      // One flip in flight at a time: committing while one is pending gives
      // EBUSY. Waiting here, not after the commit, lets the next frame render
      // while this one waits for its vblank.
      if (!wait_for_flip() || !queue_flip(fb)) {
        const int e = errno;
        gbm_surface_release_buffer(surface_, bo);
        pause(e);
        return;
      }
      pending_ = bo;
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
      wait_for_flip();
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
        const KmsPropertyIds& p = out_.props;
        req_.clear();
        req_.add(out_.crtc_id, p.crtc_active, 0);
        req_.add(out_.plane_id, p.plane_fb_id, 0);
        req_.add(out_.plane_id, p.plane_crtc_id, 0);
        done = req_.commit(out_.fd, DRM_MODE_ATOMIC_ALLOW_MODESET, nullptr) == 0;
        if (!done)
          LOG_WARN("drm: switching the CRTC off failed (%s); trying DPMS",
                   errno_string(errno).c_str());
      } else {
        done = true;  // present() modesets (ACTIVE=1) with the next frame
      }
      if (done) needs_modeset_ = !on ? true : needs_modeset_;
    }
    if (!done) done = set_dpms(on);
    if (done) {
      screen_on_ = on;
      resync_sequence_ = true;
      LOG_INFO("drm: screen %s (%s)", on ? "on" : "off",
               out_.atomic ? "CRTC ACTIVE" : "connector DPMS");
    }
    return done;
  }

  void finish() override { wait_for_flip(); }

  // --- Losing and regaining DRM master ------------------------------------
  // Another program (a VT switch through logind, a second compositor, a
  // debugging tool) took DRM master: nothing can be shown until it gives it
  // back. Candela keeps running (animation, inputs, control socket), renders
  // at the retry rate and asks for master again with a growing interval.
  void pause(int e) {
    paused_ = true;
    paused_since_ = std::chrono::steady_clock::now();
    retry_ms_ = kFirstRetryMs;
    next_retry_ = paused_since_ + std::chrono::milliseconds(retry_ms_);
    ++pauses_;
    LOG_WARN(
        "drm: lost the display on %s (%s: another program holds DRM master): pausing, asking for "
        "it again at most %d ms apart",
        out_.connector_name.c_str(), errno_string(e).c_str(), kMaxRetryMs);
  }

  // Master again and the mode set with this frame: true (then showing it).
  bool try_resume(uint32_t fb) {
    const auto now = std::chrono::steady_clock::now();
    if (now < next_retry_) return false;
    if ((drmIsMaster(out_.fd) || drmSetMaster(out_.fd) == 0) && modeset(fb)) {
      paused_ = false;
      LOG_INFO("drm: DRM master is back after %.1f s: presenting on %s again",
               std::chrono::duration<double>(now - paused_since_).count(),
               out_.connector_name.c_str());
      return true;
    }
    retry_ms_ = std::min(retry_ms_ * 2, kMaxRetryMs);
    next_retry_ = now + std::chrono::milliseconds(retry_ms_);
    return false;
  }

  // Paced by the retries while nothing is shown (no vblank to wait for).
  void wait_for_retry() const { std::this_thread::sleep_until(next_retry_); }

 private:
  // --- Connector hot-plug -------------------------------------------------
  // udev's "drm" uevents (a change of the card: HOTPLUG=1 from the driver's
  // connector polling or interrupt, or a synthetic `change`) make the
  // connectors be looked at again: a screen that appears is driven with the
  // mode chosen again, one that goes away pauses drawing (CRTC off).
  void open_hotplug_monitor() {
    struct stat st {};
    if (fstat(out_.fd, &st) == 0) card_devnum_ = st.st_rdev;
    udev_ = udev_new();
    // udevd's events where it runs (after its rules); the kernel's otherwise
    // (a container or the virtual board without udevd).
    const char* source = access("/run/udev/control", F_OK) == 0 ? "udev" : "kernel";
    if (udev_) monitor_ = udev_monitor_new_from_netlink(udev_, source);
    if (!monitor_ ||
        udev_monitor_filter_add_match_subsystem_devtype(monitor_, "drm", nullptr) < 0 ||
        udev_monitor_enable_receiving(monitor_) < 0) {
      LOG_WARN(
          "drm: cannot listen for hot-plug uevents (%s): without a screen the connectors are "
          "looked at every %d ms instead",
          errno_string(errno).c_str(), kReprobeMs);
      if (monitor_) udev_monitor_unref(monitor_);
      monitor_ = nullptr;
      return;
    }
    uevent_fd_ = udev_monitor_get_fd(monitor_);
    LOG_INFO("drm: following connector hot-plug on %s through %s uevents", out_.device.c_str(),
             source);
  }

  void close_hotplug_monitor() {
    if (monitor_) udev_monitor_unref(monitor_);
    if (udev_) udev_unref(udev_);
    monitor_ = nullptr;
    udev_ = nullptr;
    uevent_fd_ = -1;
  }

  // Waits up to timeout_ms (0: not at all) for a uevent of this card, then
  // looks at the connectors again if one came.
  void follow_hotplug(int timeout_ms) {
    if (uevent_fd_ < 0) {
      if (screen_ || timeout_ms <= 0) return;
      const auto now = std::chrono::steady_clock::now();
      if (now < next_reprobe_) {
        std::this_thread::sleep_for(
            std::min(std::chrono::milliseconds(timeout_ms),
                     std::chrono::duration_cast<std::chrono::milliseconds>(next_reprobe_ - now)));
        return;
      }
      next_reprobe_ = now + std::chrono::milliseconds(kReprobeMs);
      reprobe();
      return;
    }
    pollfd p{uevent_fd_, POLLIN, 0};
    if (poll(&p, 1, timeout_ms) <= 0 || !(p.revents & POLLIN)) return;
    bool ours = false;
    while (udev_device* d = udev_monitor_receive_device(monitor_)) {
      const char* action = udev_device_get_action(d);
      if (udev_device_get_devnum(d) == card_devnum_ && action && std::strcmp(action, "change") == 0)
        ours = true;
      udev_device_unref(d);
    }
    if (ours) reprobe();
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
      wait_for_flip();
    } catch (const std::exception& e) {
      LOG_WARN("%s", e.what());
    }
    if (!paused_) {
      bool off = false;
      if (out_.atomic) {
        const KmsPropertyIds& p = out_.props;
        req_.clear();
        req_.add(out_.crtc_id, p.crtc_active, 0);
        req_.add(out_.plane_id, p.plane_fb_id, 0);
        req_.add(out_.plane_id, p.plane_crtc_id, 0);
        off = req_.commit(out_.fd, DRM_MODE_ATOMIC_ALLOW_MODESET, nullptr) == 0;
      }
      if (!off) drmModeSetCrtc(out_.fd, out_.crtc_id, 0, 0, 0, nullptr, 0, nullptr);
    }
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
    if (surface_ && (w != width_ || h != height_)) destroy_surfaces();
    width_ = w;
    height_ = h;
    if (!saved_crtc_) saved_crtc_ = drmModeGetCrtc(out_.fd, out_.crtc_id);
    if (!surface_) create_surfaces();
    if (mode_blob_) drmModeDestroyPropertyBlob(out_.fd, mode_blob_);
    mode_blob_ = 0;
    if (out_.atomic &&
        drmModeCreatePropertyBlob(out_.fd, &out_.mode, sizeof out_.mode, &mode_blob_) != 0) {
      LOG_WARN("drm: cannot create a mode blob (%s): falling back to legacy modesetting",
               errno_string(errno).c_str());
      out_.atomic = false;
    }
    if (hotplugged)
      LOG_INFO("drm: a screen on %s: mode %s; drawing on it", out_.connector_name.c_str(),
               describe_mode(out_.mode).c_str());
    needs_modeset_ = true;
    resync_sequence_ = true;
    screen_ = true;
  }

  void init_egl() {
    gbm_ = gbm_create_device(out_.fd);
    if (!gbm_) throw RuntimeError("drm: gbm_create_device failed on " + out_.device);
    if (!egl_has_extension(EGL_NO_DISPLAY, "EGL_KHR_platform_gbm") &&
        !egl_has_extension(EGL_NO_DISPLAY, "EGL_MESA_platform_gbm"))
      throw RuntimeError("drm: EGL has no GBM platform (install libegl-mesa0)");
    auto get_platform_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
        eglGetProcAddress("eglGetPlatformDisplayEXT"));
    if (!get_platform_display) throw RuntimeError("drm: no eglGetPlatformDisplayEXT");
    egl_.emplace(get_platform_display(EGL_PLATFORM_GBM_KHR, gbm_, nullptr), EGL_WINDOW_BIT,
                 static_cast<EGLint>(kFormat));
  }

  void create_surfaces() {
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
      surface_ = gbm_surface_create_with_modifiers(gbm_, static_cast<uint32_t>(width_),
                                                   static_cast<uint32_t>(height_), kFormat,
                                                   mods.data(), static_cast<unsigned>(mods.size()));
      if (!surface_)
        LOG_INFO(
            "drm: GBM cannot allocate with the plane's modifiers (%s): falling back to an "
            "implicit scan-out buffer",
            errno_string(errno).c_str());
    } else {
      LOG_INFO("drm: no modifier list to negotiate: letting GBM pick a scan-out buffer");
    }
    if (!surface_)
      surface_ =
          gbm_surface_create(gbm_, static_cast<uint32_t>(width_), static_cast<uint32_t>(height_),
                             kFormat, GBM_BO_USE_SCANOUT | GBM_BO_USE_RENDERING);
    if (!surface_)
      throw RuntimeError("drm: cannot create a " + std::to_string(width_) + "x" +
                         std::to_string(height_) + " GBM scan-out surface: " + errno_string(errno));

    auto create_surface = reinterpret_cast<PFNEGLCREATEPLATFORMWINDOWSURFACEEXTPROC>(
        eglGetProcAddress("eglCreatePlatformWindowSurfaceEXT"));
    egl_surface_ =
        create_surface
            ? create_surface(egl_->display(), egl_->config(), surface_, nullptr)
            : eglCreateWindowSurface(egl_->display(), egl_->config(),
                                     reinterpret_cast<EGLNativeWindowType>(surface_), nullptr);
    if (egl_surface_ == EGL_NO_SURFACE)
      throw RuntimeError("drm: cannot create an EGL surface on GBM: " +
                         egl_error_string(eglGetError()));
    egl_->make_current(egl_surface_);
  }

  // The framebuffer of a GBM buffer, made once per buffer (GBM reuses a few).
  uint32_t framebuffer_for(gbm_bo* bo) {
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
      if (drmModeAddFB2WithModifiers(out_.fd, w, h, format, handles, strides, offsets, modifiers,
                                     &fb, DRM_MODE_FB_MODIFIERS) != 0) {
        LOG_WARN("drm: AddFB2 with modifier 0x%llx failed (%s): trying without",
                 static_cast<unsigned long long>(modifier), errno_string(errno).c_str());
        fb = 0;
      }
    } else if (!logged_plain_fb_) {
      logged_plain_fb_ = true;
      LOG_INFO("drm: buffer modifier is %s: adding framebuffers without modifiers",
               modifier == DRM_FORMAT_MOD_INVALID ? "INVALID" : "LINEAR");
    }
    if (!fb && drmModeAddFB2(out_.fd, w, h, format, handles, strides, offsets, &fb, 0) != 0) {
      LOG_ERROR("drm: drmModeAddFB2 %ux%u failed: %s", w, h, errno_string(errno).c_str());
      return 0;
    }
    gbm_bo_set_user_data(bo, new BufferFb{out_.fd, fb}, &BufferFb::destroy);
    return fb;
  }

  // False with errno set when another program holds DRM master.
  bool modeset(uint32_t fb) {
    if (out_.atomic) {
      const KmsPropertyIds& p = out_.props;
      req_.clear();
      req_.add(out_.connector_id, p.connector_crtc_id, out_.crtc_id);
      req_.add(out_.crtc_id, p.crtc_mode_id, mode_blob_);
      req_.add(out_.crtc_id, p.crtc_active, 1);
      add_plane_properties(fb);
      // Blocking and without an event: the next present() flips onto it.
      if (req_.commit(out_.fd, DRM_MODE_ATOMIC_ALLOW_MODESET, nullptr) == 0) {
        ++modesets_;
        LOG_INFO("drm: atomic modeset %s on %s done", describe_mode(out_.mode).c_str(),
                 out_.connector_name.c_str());
        return true;
      }
      if (is_master_error(errno)) return false;
      LOG_WARN("drm: atomic modeset failed (%s): falling back to legacy modesetting",
               errno_string(errno).c_str());
      out_.atomic = false;
    }
    uint32_t connector = out_.connector_id;
    if (drmModeSetCrtc(out_.fd, out_.crtc_id, fb, 0, 0, &connector, 1, &out_.mode) != 0) {
      if (is_master_error(errno)) return false;
      throw RuntimeError("drm: cannot set mode " + describe_mode(out_.mode) + " on " +
                         out_.connector_name + ": " + errno_string(errno));
    }
    ++modesets_;
    LOG_INFO("drm: legacy modeset %s on %s done", describe_mode(out_.mode).c_str(),
             out_.connector_name.c_str());
    return true;
  }

  // Legacy DPMS through the connector's "DPMS" property.
  bool set_dpms(bool on) {
    drmModeObjectProperties* props =
        drmModeObjectGetProperties(out_.fd, out_.connector_id, DRM_MODE_OBJECT_CONNECTOR);
    uint32_t dpms = 0;
    for (uint32_t i = 0; props && i < props->count_props && !dpms; ++i) {
      drmModePropertyRes* p = drmModeGetProperty(out_.fd, props->props[i]);
      if (p && std::strcmp(p->name, "DPMS") == 0) dpms = p->prop_id;
      drmModeFreeProperty(p);
    }
    drmModeFreeObjectProperties(props);
    if (!dpms) {
      LOG_WARN("drm: %s has no DPMS property; the screen stays lit (showing black)",
               out_.connector_name.c_str());
      return false;
    }
    if (drmModeConnectorSetProperty(out_.fd, out_.connector_id, dpms,
                                    on ? DRM_MODE_DPMS_ON : DRM_MODE_DPMS_OFF) != 0) {
      LOG_WARN("drm: DPMS %s on %s failed: %s", on ? "On" : "Off", out_.connector_name.c_str(),
               errno_string(errno).c_str());
      return false;
    }
    return true;
  }

  void add_plane_properties(uint32_t fb) {
    const KmsPropertyIds& p = out_.props;
    const uint32_t plane = out_.plane_id;
    const uint64_t w = static_cast<uint64_t>(width_), h = static_cast<uint64_t>(height_);
    req_.add(plane, p.plane_fb_id, fb);
    req_.add(plane, p.plane_crtc_id, out_.crtc_id);
    req_.add(plane, p.plane_src_x, 0);
    req_.add(plane, p.plane_src_y, 0);
    req_.add(plane, p.plane_src_w, w << 16);
    req_.add(plane, p.plane_src_h, h << 16);
    req_.add(plane, p.plane_crtc_x, 0);
    req_.add(plane, p.plane_crtc_y, 0);
    req_.add(plane, p.plane_crtc_w, w);
    req_.add(plane, p.plane_crtc_h, h);
  }

  // False with errno set when another program holds DRM master.
  bool queue_flip(uint32_t fb) {
    if (out_.atomic) {
      req_.clear();
      add_plane_properties(fb);
      if (req_.commit(out_.fd, DRM_MODE_ATOMIC_NONBLOCK | DRM_MODE_PAGE_FLIP_EVENT, this) == 0) {
        flip_pending_ = true;
        return true;
      }
      if (is_master_error(errno)) return false;
      LOG_WARN("drm: atomic page flip failed (%s): falling back to legacy page flips",
               errno_string(errno).c_str());
      out_.atomic = false;
    }
    if (drmModePageFlip(out_.fd, out_.crtc_id, fb, DRM_MODE_PAGE_FLIP_EVENT, this) != 0) {
      if (is_master_error(errno)) return false;
      throw RuntimeError("drm: page flip on " + out_.connector_name +
                         " failed: " + errno_string(errno));
    }
    flip_pending_ = true;
    return true;
  }

  // False (errno EACCES) when the flip never completed because another
  // program took DRM master meanwhile; throws on any other failure.
  bool wait_for_flip() {
    while (flip_pending_) {
      pollfd p{out_.fd, POLLIN, 0};
      const int r = poll(&p, 1, kFlipTimeoutMs);
      if (r < 0) {
        if (errno == EINTR) continue;
        throw RuntimeError("drm: poll on " + out_.device + " failed: " + errno_string(errno));
      }
      if (r == 0) {
        flip_pending_ = false;  // do not wait for it again
        if (!drmIsMaster(out_.fd)) {
          if (pending_) gbm_surface_release_buffer(surface_, pending_);
          pending_ = nullptr;
          errno = EACCES;
          return false;
        }
        throw RuntimeError("drm: a page flip did not complete within " +
                           std::to_string(kFlipTimeoutMs) + " ms");
      }
      if (drmHandleEvent(out_.fd, &event_context_) != 0)
        throw RuntimeError("drm: reading DRM events failed: " + errno_string(errno));
    }
    return true;
  }

  static void on_page_flip(int, unsigned sequence, unsigned, unsigned, void* data) {
    auto* self = static_cast<DrmDisplay*>(data);
    self->flip_pending_ = false;
    if (self->front_) gbm_surface_release_buffer(self->surface_, self->front_);
    self->front_ = self->pending_;
    self->pending_ = nullptr;
    // The flip event carries the vblank counter: a gap of more than one
    // between flips means vblanks went by showing an old frame.
    if (self->flips_done_ > 0 && !self->resync_sequence_) {
      const uint32_t gap = sequence - self->last_sequence_;
      if (gap > 1) self->missed_ += gap - 1;
    }
    self->last_sequence_ = sequence;
    self->resync_sequence_ = false;
    ++self->flips_done_;
  }

  void restore_crtc() {
    if (presented_ == 0 || !screen_) return;  // never touched the display, or it is gone
    if (paused_) {
      LOG_INFO("drm: another program holds the display: leaving CRTC %u as it is", out_.crtc_id);
      return;
    }
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
               what.c_str(), errno_string(errno).c_str());
  }

  // The GBM and EGL surfaces gone; the context stays current without one
  // (keep_context) so GL objects live on for the next size.
  void destroy_surfaces(bool keep_context = true) {
    if (egl_ && egl_surface_ != EGL_NO_SURFACE) {
      eglMakeCurrent(egl_->display(), EGL_NO_SURFACE, EGL_NO_SURFACE,
                     keep_context ? egl_->context() : EGL_NO_CONTEXT);
      eglDestroySurface(egl_->display(), egl_surface_);
      egl_surface_ = EGL_NO_SURFACE;
    }
    if (surface_) {
      if (pending_) gbm_surface_release_buffer(surface_, pending_);
      if (front_) gbm_surface_release_buffer(surface_, front_);
      pending_ = front_ = nullptr;
      gbm_surface_destroy(surface_);  // removes the framebuffers (BufferFb::destroy)
      surface_ = nullptr;
    }
  }

  void release() {
    if (egl_) eglMakeCurrent(egl_->display(), EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    destroy_surfaces(false);
    egl_.reset();
    if (gbm_) gbm_device_destroy(gbm_);
    gbm_ = nullptr;
    if (mode_blob_) drmModeDestroyPropertyBlob(out_.fd, mode_blob_);
    mode_blob_ = 0;
    if (saved_crtc_) drmModeFreeCrtc(saved_crtc_);
    saved_crtc_ = nullptr;
  }

  DisplayOptions options_;  // the mode is chosen again by them on hot-plug
  KmsOutput out_;           // closes the card and drops master last
  int width_ = 0, height_ = 0;
  drmModeCrtc* saved_crtc_ = nullptr;
  gbm_device* gbm_ = nullptr;
  gbm_surface* surface_ = nullptr;
  std::optional<EglContext> egl_;
  EGLSurface egl_surface_ = EGL_NO_SURFACE;
  AtomicRequest req_;
  uint32_t mode_blob_ = 0;
  drmEventContext event_context_{};
  gbm_bo* front_ = nullptr;    // on screen
  gbm_bo* pending_ = nullptr;  // queued to flip at the next vblank
  bool flip_pending_ = false;
  bool logged_plain_fb_ = false;
  bool screen_on_ = true;
  bool needs_modeset_ = false;    // the CRTC was switched off: the next present() modesets
  bool resync_sequence_ = false;  // the vblank counter jumps over an off period
  uint64_t presented_ = 0;
  uint64_t flips_done_ = 0;
  uint32_t last_sequence_ = 0;
  int64_t missed_ = 0;
  bool paused_ = false;  // DRM master lost: nothing shown until try_resume()
  int retry_ms_ = kFirstRetryMs;
  uint64_t pauses_ = 0, modesets_ = 0;
  std::chrono::steady_clock::time_point paused_since_{}, next_retry_{};
  bool screen_ = false;  // a connected connector with its mode set up
  uint64_t screens_lost_ = 0;
  udev* udev_ = nullptr;
  udev_monitor* monitor_ = nullptr;
  int uevent_fd_ = -1;  // the monitor's (non-blocking); -1: re-probe every kReprobeMs
  dev_t card_devnum_ = 0;
  std::chrono::steady_clock::time_point next_reprobe_{};
};

}  // namespace

std::unique_ptr<Display> open_drm_display(const DisplayOptions& options) {
  return std::make_unique<DrmDisplay>(options);
}

}  // namespace candela
