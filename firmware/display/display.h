// "A place to draw": the one interface the frame loop knows. Backends (one
// file each): drm_display.cpp (kiosk), window_display.cpp (desktop emulator),
// headless_display.cpp (tests, CI, frame dumps). open_display() picks one.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>

union _XEvent;  // <X11/Xlib.h>'s XEvent, for DisplayEvents::on_x11_event

namespace candela {

// Keys the emulator and kiosk understand; backends translate their own codes.
enum class Key { kQuit, kLeft, kRight, kUp, kDown, kSpace, kBlowOut, kOther };

class DisplayEvents {
 public:
  virtual ~DisplayEvents() = default;
  virtual void on_key(Key key) = 0;
  // The window backend hands every X11 event here first (pointer, keys with
  // their text, focus, resize: what a desktop UI such as the studio needs).
  // Returning true consumes it: no on_key(), no quit on Esc/q. The default
  // consumes nothing, so the frame loop and the other backends never see it.
  virtual bool on_x11_event(const _XEvent& event) {
    (void)event;
    return false;
  }
};

struct DisplayOptions {
  std::string kind = "auto";  // auto | drm | window | headless
  int width = 0;              // 0: the backend's default (DRM: the connector's preferred mode)
  int height = 0;
  int refresh_hz = 0;      // DRM mode choice; 0: preferred
  std::string drm_device;  // e.g. /dev/dri/card1; empty: the first card with a connected connector
  std::string out_path;    // headless: PNG folder, .y4m or .mp4; empty: render only
  // Headless video through ffmpeg (.mp4, .mkv, .webm): the run's sound (a
  // .wav) to mux into it once both are finished; empty or no samples: none.
  std::string sound_path;
  int fps = 60;  // the rate frames are written at (headless video)
  bool vsync = true;
  std::string title = "Candela";  // window: its title
};

class Display {
 public:
  virtual ~Display() = default;
  virtual std::string_view name() const = 0;
  virtual int width() const = 0;
  virtual int height() const = 0;
  // True when present() waits for the display's vertical blank.
  virtual bool paced_by_vsync() const = 0;
  // Binds the framebuffer this frame draws into and sets the viewport.
  virtual void begin_frame() = 0;
  // Shows (or writes) the frame. Never allocates once running.
  virtual void present() = 0;
  // Delivers pending input; returns false once the user asked to quit.
  virtual bool poll_events(DisplayEvents& events) = 0;
  // Vblanks that passed without a new frame, or -1 where the backend cannot tell.
  virtual int64_t missed_vblanks() const { return -1; }
  // Switches the screen itself off or on (the frame loop then stops or
  // resumes presenting). DRM: the CRTC inactive (atomic) or the connector's
  // DPMS off (legacy); elsewhere nothing to switch. Never throws: a refusal
  // is logged. Returns whether the screen was really switched.
  virtual bool set_screen_power(bool on) {
    (void)on;
    return false;
  }
  // False while there is nowhere to show frames (DRM: no monitor connected
  // or switched on, with --display drm). The frame loop then draws nothing
  // and calls wait_for_screen() instead, so it is alive but idle.
  virtual bool screen_present() const { return true; }
  // Waits at most timeout_ms for a screen to appear (DRM: hot-plug uevents,
  // the connectors probed again and the mode chosen again); returns
  // screen_present().
  virtual bool wait_for_screen(int timeout_ms) {
    (void)timeout_ms;
    return true;
  }
  // Waits until everything written so far is on disk (headless). Throws on I/O failure.
  virtual void finish() {}
};

// Opens the named backend, or for "auto" tries drm, window, headless in that
// order and logs why each skipped one was skipped. Throws RuntimeError if none opens.
std::unique_ptr<Display> open_display(const DisplayOptions& options);

// The backends, each throwing RuntimeError with the reason it cannot open.
std::unique_ptr<Display> open_drm_display(const DisplayOptions& options);
std::unique_ptr<Display> open_window_display(const DisplayOptions& options);
std::unique_ptr<Display> open_headless_display(const DisplayOptions& options);

}  // namespace candela
