// Dear ImGui's platform side on X11 (ImGui ships none): X events from the
// window backend (DisplayEvents::on_x11_event) -> ImGuiIO: mouse position,
// buttons and wheel, keys and modifiers, typed text (UTF-8, through the X
// input method), focus; plus the display size and the time step at each new
// frame.
#pragma once

#include <chrono>

union _XEvent;

namespace candela::studio {

// io.KeysDown[] index of a letter key a..z (for shortcuts ImGuiKey_ lacks,
// e.g. ImGui::IsKeyPressed(letter_key('q')) with io.KeyCtrl).
constexpr int letter_key(char c) { return 256 + (c - 'a'); }

class X11Platform {
 public:
  X11Platform();  // after ImGui::CreateContext(): fills io.KeyMap
  // Feeds one event into ImGuiIO; true when it was input ImGui takes.
  bool handle(const _XEvent& event);
  // Before ImGui::NewFrame(): display size (the window's, in pixels) and
  // the time since the last frame (a fixed step when `fixed_dt` > 0, for
  // reproducible scripted runs).
  void new_frame(int width, int height, double fixed_dt = 0);
  // Asks the window manager (or the X server) for a new window size; the
  // window backend then sees the ConfigureNotify. False before any event
  // named the window.
  bool resize_window(int width, int height);
  // Real input for scripts: an event sent to the window through the X server
  // (XSendEvent, then XSync: it is in the queue at the next poll), so it takes
  // the whole way a user's does. x, y: window pixels; `ctrl`: Control held.
  // button: 1 left, 2 middle, 3 right, 4/5 wheel. False before the window is known.
  bool send_button(int button, bool down, int x, int y, bool ctrl = false);
  bool send_motion(int x, int y);
  bool send_key(const char* keysym_name, bool down, bool ctrl = false);

 private:
  std::chrono::steady_clock::time_point last_;
  bool first_ = true;
  void* x_display_ = nullptr;  // ::Display*, from the events
  unsigned long x_window_ = 0;
  // The X input method's context for typed text (UTF-8, compose keys); made
  // at the first key press, null where the server offers none (then Latin-1
  // and Unicode keysyms). It lives as long as the display connection.
  void* input_context(void* display, unsigned long window);
  bool im_tried_ = false;
  void* xic_ = nullptr;
};

}  // namespace candela::studio
