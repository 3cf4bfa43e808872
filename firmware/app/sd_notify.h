// systemd's service notification protocol (sd_notify(3)), spoken directly:
// datagrams on the AF_UNIX socket named by $NOTIFY_SOCKET ("/path" or
// "@abstract"), so the kiosk needs no libsystemd. With the unit's
// Type=notify and WatchdogSec=:
//   READY=1    once, after the first frame is presented (not at start-up:
//              a kiosk that cannot show is not ready)
//   WATCHDOG=1 from the frame loop after a presented frame, at most every
//              WATCHDOG_USEC/2: a hung GPU or loop stops the pings and
//              systemd restarts it
//   STATUS=    the scene and the frame rate, about once a second ("SCENE:
//              screen off" while the screen is switched off)
//   RELOADING=1 (with MONOTONIC_USEC=) when a reload (SIGHUP, `reload`)
//              begins, READY=1 again when it is done
//   WATCHDOG=1 also while the screen is switched off on purpose, or while
//              no screen is connected (STATUS=SCENE: waiting for a screen;
//              the loop then sleeps but is alive)
//   STOPPING=1 when the loop ends
// Sends are non-blocking (MSG_DONTWAIT) from fixed buffers: nothing in the
// frame loop allocates or waits. Without $NOTIFY_SOCKET it does nothing.
#pragma once

#include <sys/socket.h>
#include <sys/un.h>

#include <chrono>
#include <cstdint>
#include <string>

namespace candela {

class SdNotify {
 public:
  using Clock = std::chrono::steady_clock;
  SdNotify() = default;
  // Reads and unsets NOTIFY_SOCKET, WATCHDOG_USEC and WATCHDOG_PID (so
  // children such as ffmpeg do not inherit them). `scene` names the scene in
  // STATUS= (its file name). Call before other threads start.
  static SdNotify from_environment(const std::string& scene);
  SdNotify(SdNotify&& o) noexcept;
  SdNotify& operator=(SdNotify&& o) noexcept;
  SdNotify(const SdNotify&) = delete;
  SdNotify& operator=(const SdNotify&) = delete;
  ~SdNotify();

  bool enabled() const { return fd_ >= 0; }
  // 0: no watchdog asked for (or for another process).
  int64_t watchdog_interval_ns() const { return ping_ns_; }
  // After each presented frame (frames: how many so far, this one included).
  void frame_presented(uint64_t frames, Clock::time_point now);
  // A scene swapped in: STATUS= names it from now on (frame loop; no allocation).
  void set_scene(const std::string& scene);
  // The screen is off on purpose (or, `why` = "waiting for a screen", none
  // is connected) and the loop is alive: STATUS=SCENE: WHY once, READY=1 if
  // not sent yet, then watchdog pings only. `why` must outlive the call
  // sequence (a string literal).
  void idle(Clock::time_point now, const char* why = "screen off");
  // Any thread (a send on a fixed socket): a reload begins / is done.
  void reloading();
  void reloaded();
  void stopping();

 private:
  void send(const char* msg, int len);
  int fd_ = -1;
  sockaddr_un addr_{};
  socklen_t addr_len_ = 0;
  int64_t ping_ns_ = 0;
  bool ready_ = false;
  const char* idle_ = nullptr;  // why the loop idles: STATUS= said so once
  Clock::time_point next_ping_{};
  Clock::time_point status_since_{};
  uint64_t status_frames_ = 0;
  char scene_[80] = {};
};

}  // namespace candela
