#include "x11_platform.h"

#include <X11/Xlib.h>
#include <X11/Xutil.h>
#include <X11/keysym.h>
#include <imgui.h>

namespace candela::studio {
namespace {

// io.KeysDown[] is indexed by ImGuiKey_ values themselves (io.KeyMap[k] = k).
int imgui_key_of(KeySym s) {
  switch (s) {
    case XK_Tab:
    case XK_ISO_Left_Tab:
      return ImGuiKey_Tab;
    case XK_Left:
      return ImGuiKey_LeftArrow;
    case XK_Right:
      return ImGuiKey_RightArrow;
    case XK_Up:
      return ImGuiKey_UpArrow;
    case XK_Down:
      return ImGuiKey_DownArrow;
    case XK_Page_Up:
      return ImGuiKey_PageUp;
    case XK_Page_Down:
      return ImGuiKey_PageDown;
    case XK_Home:
      return ImGuiKey_Home;
    case XK_End:
      return ImGuiKey_End;
    case XK_Insert:
      return ImGuiKey_Insert;
    case XK_Delete:
      return ImGuiKey_Delete;
    case XK_BackSpace:
      return ImGuiKey_Backspace;
    case XK_space:
      return ImGuiKey_Space;
    case XK_Return:
      return ImGuiKey_Enter;
    case XK_Escape:
      return ImGuiKey_Escape;
    case XK_KP_Enter:
      return ImGuiKey_KeyPadEnter;
    case XK_a:
    case XK_A:
      return ImGuiKey_A;
    case XK_c:
    case XK_C:
      return ImGuiKey_C;
    case XK_v:
    case XK_V:
      return ImGuiKey_V;
    case XK_x:
    case XK_X:
      return ImGuiKey_X;
    case XK_y:
    case XK_Y:
      return ImGuiKey_Y;
    case XK_z:
    case XK_Z:
      return ImGuiKey_Z;
    default:
      return -1;
  }
}

void set_modifiers(ImGuiIO& io, unsigned state) {
  io.KeyCtrl = (state & ControlMask) != 0;
  io.KeyShift = (state & ShiftMask) != 0;
  io.KeyAlt = (state & Mod1Mask) != 0;
  io.KeySuper = (state & Mod4Mask) != 0;
}

}  // namespace

X11Platform::X11Platform() {
  ImGuiIO& io = ImGui::GetIO();
  for (int k = 0; k < ImGuiKey_COUNT; ++k) io.KeyMap[k] = k;
  io.BackendPlatformName = "candela_x11";
}

bool X11Platform::handle(const XEvent& ev) {
  ImGuiIO& io = ImGui::GetIO();
  x_display_ = ev.xany.display;
  x_window_ = ev.xany.window;
  switch (ev.type) {
    case MotionNotify:
      io.MousePos = ImVec2(static_cast<float>(ev.xmotion.x), static_cast<float>(ev.xmotion.y));
      return true;
    case ButtonPress:
    case ButtonRelease: {
      const bool down = ev.type == ButtonPress;
      io.MousePos = ImVec2(static_cast<float>(ev.xbutton.x), static_cast<float>(ev.xbutton.y));
      set_modifiers(io, ev.xbutton.state);
      switch (ev.xbutton.button) {
        case Button1:
          io.MouseDown[0] = down;
          break;
        case Button2:
          io.MouseDown[2] = down;
          break;
        case Button3:
          io.MouseDown[1] = down;
          break;
        case Button4:  // wheel up
          if (down) io.MouseWheel += 1;
          break;
        case Button5:
          if (down) io.MouseWheel -= 1;
          break;
        case 6:  // horizontal wheel
          if (down) io.MouseWheelH += 1;
          break;
        case 7:
          if (down) io.MouseWheelH -= 1;
          break;
        default:
          break;
      }
      return true;
    }
    case KeyPress:
    case KeyRelease: {
      XKeyEvent key = ev.xkey;  // XLookupString wants a non-const event
      const bool down = ev.type == KeyPress;
      // Modifiers as they are after this event (the state field is before it).
      unsigned state = key.state;
      const KeySym plain = XLookupKeysym(&key, 0);
      const unsigned mask = plain == XK_Control_L || plain == XK_Control_R ? ControlMask
                            : plain == XK_Shift_L || plain == XK_Shift_R   ? ShiftMask
                            : plain == XK_Alt_L || plain == XK_Alt_R       ? Mod1Mask
                            : plain == XK_Super_L || plain == XK_Super_R   ? Mod4Mask
                                                                           : 0u;
      state = down ? (state | mask) : (state & ~mask);
      set_modifiers(io, state);
      const int k = imgui_key_of(plain);
      if (k >= 0) io.KeysDown[k] = down;
      if (plain >= XK_a && plain <= XK_z)
        io.KeysDown[letter_key(static_cast<char>('a' + (plain - XK_a)))] = down;
      if (down && !(state & ControlMask)) {
        char text[64];
        KeySym sym = 0;
        if (auto* ic = static_cast<XIC>(input_context(key.display, key.window))) {
          // UTF-8 whatever the keyboard layout (Greek, Cyrillic, the euro sign...).
          Status status = 0;
          const int n = Xutf8LookupString(ic, &key, text, sizeof text - 1, &sym, &status);
          if ((status == XLookupChars || status == XLookupBoth) && n > 0) {
            text[n] = '\0';
            const auto c = static_cast<unsigned char>(text[0]);
            if (c >= 0x20 && c != 0x7f) io.AddInputCharactersUTF8(text);
          }
        } else {
          // No input method: Latin-1 bytes are code points, and a Unicode
          // keysym (0x01000000 + code point) is its character.
          const int n = XLookupString(&key, text, sizeof text - 1, &sym, nullptr);
          for (int i = 0; i < n; ++i) {
            const auto c = static_cast<unsigned char>(text[i]);
            if (c >= 0x20 && c != 0x7f) io.AddInputCharacter(c);
          }
          if (n == 0 && sym >= 0x01000100 && sym <= 0x0110ffff)
            io.AddInputCharacter(static_cast<unsigned>(sym - 0x01000000));
        }
      }
      return true;
    }
    case MappingNotify: {  // the keyboard's map changed (e.g. a script's spare keycode)
      XMappingEvent m = ev.xmapping;
      XRefreshKeyboardMapping(&m);
      return false;
    }
    case FocusIn:
    case FocusOut:
      io.AddFocusEvent(ev.type == FocusIn);
      return true;
    case LeaveNotify:
      io.MousePos = ImVec2(-FLT_MAX, -FLT_MAX);
      return true;
    default:
      return false;
  }
}

bool X11Platform::resize_window(int width, int height) {
  if (!x_display_ || !x_window_) return false;
  auto* dpy = static_cast<::Display*>(x_display_);
  XResizeWindow(dpy, x_window_, static_cast<unsigned>(width), static_cast<unsigned>(height));
  XFlush(dpy);
  return true;
}

namespace {
template <typename Fill>
bool send_event(void* display, unsigned long window, long mask, Fill fill) {
  if (!display || !window) return false;
  auto* dpy = static_cast<::Display*>(display);
  XEvent ev{};
  fill(ev, dpy);
  ev.xany.display = dpy;
  ev.xany.window = window;
  XSendEvent(dpy, window, False, mask, &ev);
  XSync(dpy, False);
  return true;
}
}  // namespace

bool X11Platform::send_button(int button, bool down, int x, int y, bool ctrl) {
  return send_event(x_display_, x_window_, down ? ButtonPressMask : ButtonReleaseMask,
                    [&](XEvent& ev, ::Display*) {
                      ev.type = down ? ButtonPress : ButtonRelease;
                      ev.xbutton.button = static_cast<unsigned>(button);
                      ev.xbutton.x = x;
                      ev.xbutton.y = y;
                      ev.xbutton.state = ctrl ? ControlMask : 0;
                      ev.xbutton.same_screen = True;
                    });
}

bool X11Platform::send_motion(int x, int y) {
  return send_event(x_display_, x_window_, PointerMotionMask, [&](XEvent& ev, ::Display*) {
    ev.type = MotionNotify;
    ev.xmotion.x = x;
    ev.xmotion.y = y;
    ev.xmotion.same_screen = True;
  });
}

void* X11Platform::input_context(void* display, unsigned long window) {
  if (im_tried_) return xic_;
  im_tried_ = true;
  auto* dpy = static_cast<::Display*>(display);
  XIM im = XOpenIM(dpy, nullptr, nullptr, nullptr);
  if (!im) return nullptr;
  xic_ =
      XCreateIC(im, XNInputStyle, XIMPreeditNothing | XIMStatusNothing, XNClientWindow,
                static_cast<Window>(window), XNFocusWindow, static_cast<Window>(window), nullptr);
  if (!xic_) XCloseIM(im);
  return xic_;
}

// The keycode that types `sym`: the keyboard's own, or else a spare keycode
// mapped to it (as xdotool does), so scripts can type any character.
static KeyCode keycode_for(::Display* dpy, KeySym sym) {
  if (const KeyCode k = XKeysymToKeycode(dpy, sym)) return k;
  int lo = 0, hi = 0, per = 0;
  XDisplayKeycodes(dpy, &lo, &hi);
  KeySym* map = XGetKeyboardMapping(dpy, static_cast<KeyCode>(lo), hi - lo + 1, &per);
  if (!map) return 0;
  KeyCode spare = 0;
  for (int k = hi; k >= lo && !spare; --k) {
    bool empty = true;
    for (int i = 0; i < per; ++i) empty = empty && map[(k - lo) * per + i] == NoSymbol;
    if (empty) spare = static_cast<KeyCode>(k);
  }
  XFree(map);
  if (!spare) return 0;
  KeySym both[2] = {sym, sym};
  XChangeKeyboardMapping(dpy, spare, 2, both, 1);
  XSync(dpy, False);
  return spare;
}

bool X11Platform::send_key(const char* name, bool down, bool ctrl) {
  const KeySym sym = XStringToKeysym(name);
  if (sym == NoSymbol) return false;
  return send_event(x_display_, x_window_, down ? KeyPressMask : KeyReleaseMask,
                    [&](XEvent& ev, ::Display* dpy) {
                      ev.type = down ? KeyPress : KeyRelease;
                      ev.xkey.keycode = keycode_for(dpy, sym);
                      ev.xkey.state = ctrl ? ControlMask : 0;
                      ev.xkey.same_screen = True;
                    });
}

void X11Platform::new_frame(int width, int height, double fixed_dt) {
  ImGuiIO& io = ImGui::GetIO();
  io.DisplaySize = ImVec2(static_cast<float>(width), static_cast<float>(height));
  const auto now = std::chrono::steady_clock::now();
  double dt = first_ ? 1.0 / 60 : std::chrono::duration<double>(now - last_).count();
  if (fixed_dt > 0) dt = fixed_dt;
  if (dt <= 0) dt = 1e-4;
  io.DeltaTime = static_cast<float>(dt);
  last_ = now;
  first_ = false;
}

}  // namespace candela::studio
