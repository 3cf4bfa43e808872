#include "app/sd_notify.h"

#include <time.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <utility>

#include "core/log.h"

namespace candela {

SdNotify SdNotify::from_environment(const std::string& scene) {
  SdNotify n;
  const char* sock = std::getenv("NOTIFY_SOCKET");
  const char* wd_usec = std::getenv("WATCHDOG_USEC");
  const char* wd_pid = std::getenv("WATCHDOG_PID");
  const std::string path = sock ? sock : "";
  int64_t usec = 0;
  if (wd_usec) {
    char* end = nullptr;
    errno = 0;
    const long long v = std::strtoll(wd_usec, &end, 10);
    if (errno == 0 && end != wd_usec && *end == '\0' && v > 0) usec = v;
  }
  // WATCHDOG_PID: the watchdog is for that process only (sd_watchdog_enabled(3)).
  if (wd_pid && std::strtoll(wd_pid, nullptr, 10) != static_cast<long long>(getpid())) usec = 0;
  unsetenv("NOTIFY_SOCKET");
  unsetenv("WATCHDOG_USEC");
  unsetenv("WATCHDOG_PID");
  if (path.empty()) return n;
  if ((path[0] != '/' && path[0] != '@') || path.size() >= sizeof(n.addr_.sun_path)) {
    LOG_WARN(
        "NOTIFY_SOCKET: expected an absolute path or @name shorter than %zu bytes; not notifying",
        sizeof(n.addr_.sun_path));
    return n;
  }
  n.fd_ = socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
  if (n.fd_ < 0) {
    LOG_WARN("NOTIFY_SOCKET: socket: %s; not notifying", std::strerror(errno));
    return n;
  }
  n.addr_.sun_family = AF_UNIX;
  std::memcpy(n.addr_.sun_path, path.data(), path.size());
  if (path[0] == '@') n.addr_.sun_path[0] = '\0';  // the abstract namespace
  n.addr_len_ = static_cast<socklen_t>(offsetof(sockaddr_un, sun_path) + path.size());
  // Ping at half the period, as sd_watchdog_enabled(3) advises.
  n.ping_ns_ = usec * 1000 / 2;
  const size_t slash = scene.find_last_of('/');
  std::snprintf(n.scene_, sizeof(n.scene_), "%s",
                (slash == std::string::npos ? scene : scene.substr(slash + 1)).c_str());
  return n;
}

SdNotify::SdNotify(SdNotify&& o) noexcept { *this = std::move(o); }

SdNotify& SdNotify::operator=(SdNotify&& o) noexcept {
  if (this != &o) {
    if (fd_ >= 0) close(fd_);
    fd_ = std::exchange(o.fd_, -1);
    addr_ = o.addr_;
    addr_len_ = o.addr_len_;
    ping_ns_ = o.ping_ns_;
    ready_ = o.ready_;
    next_ping_ = o.next_ping_;
    status_since_ = o.status_since_;
    status_frames_ = o.status_frames_;
    std::memcpy(scene_, o.scene_, sizeof(scene_));
  }
  return *this;
}

SdNotify::~SdNotify() {
  if (fd_ >= 0) close(fd_);
}

void SdNotify::send(const char* msg, int len) {
  if (len <= 0) return;
  // Non-blocking: a full or gone receiver drops the message, never stalls a frame.
  (void)sendto(fd_, msg, static_cast<size_t>(len), MSG_DONTWAIT | MSG_NOSIGNAL,
               reinterpret_cast<const sockaddr*>(&addr_), addr_len_);
}

void SdNotify::frame_presented(uint64_t frames, Clock::time_point now) {
  if (fd_ < 0) return;
  char msg[160];
  if (!ready_) {
    ready_ = true;
    status_since_ = now;
    status_frames_ = frames;
    send(msg, std::snprintf(msg, sizeof(msg), "READY=1\nSTATUS=%s: frame %llu presented", scene_,
                            static_cast<unsigned long long>(frames)));
  }
  if (idle_) {  // the screen back on: the rate counts from now
    idle_ = nullptr;
    status_since_ = now;
    status_frames_ = frames;
  }
  if (ping_ns_ > 0 && now >= next_ping_) {
    next_ping_ = now + std::chrono::nanoseconds(ping_ns_);
    send("WATCHDOG=1", 10);
  }
  const int64_t since =
      std::chrono::duration_cast<std::chrono::milliseconds>(now - status_since_).count();
  if (since >= 1000) {
    // Tenths of a frame per second, in integers: no floating-point formatting.
    const uint64_t tenths = (frames - status_frames_) * 10000 / static_cast<uint64_t>(since);
    send(msg, std::snprintf(msg, sizeof(msg), "STATUS=%s: %llu.%llu fps", scene_,
                            static_cast<unsigned long long>(tenths / 10),
                            static_cast<unsigned long long>(tenths % 10)));
    status_since_ = now;
    status_frames_ = frames;
  }
}

void SdNotify::set_scene(const std::string& scene) {
  const size_t slash = scene.find_last_of('/');
  const char* name = scene.c_str() + (slash == std::string::npos ? 0 : slash + 1);
  std::snprintf(scene_, sizeof(scene_), "%s", name);
}

void SdNotify::idle(Clock::time_point now, const char* why) {
  if (fd_ < 0) return;
  if (!idle_ || std::strcmp(idle_, why) != 0) {  // `systemctl status` says so, not the last rate
    idle_ = why;
    char msg[160];
    send(msg, std::snprintf(msg, sizeof(msg), "%sSTATUS=%s: %s", ready_ ? "" : "READY=1\n", scene_,
                            why));
    // Started with the screen scheduled off or no screen connected: running is ready.
    ready_ = true;
    status_since_ = now;
  }
  if (ping_ns_ <= 0 || now < next_ping_) return;
  next_ping_ = now + std::chrono::nanoseconds(ping_ns_);
  send("WATCHDOG=1", 10);
}

void SdNotify::reloading() {
  if (fd_ < 0) return;
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  char msg[96];
  send(msg, std::snprintf(msg, sizeof(msg), "RELOADING=1\nMONOTONIC_USEC=%llu",
                          static_cast<unsigned long long>(ts.tv_sec) * 1000000ULL +
                              static_cast<unsigned long long>(ts.tv_nsec) / 1000ULL));
}

void SdNotify::reloaded() {
  if (fd_ >= 0) send("READY=1", 7);
}

void SdNotify::stopping() {
  if (fd_ >= 0) send("STOPPING=1", 10);
}

}  // namespace candela
