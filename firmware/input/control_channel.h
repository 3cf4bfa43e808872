// The control channel: a UNIX stream socket (owner-only, 0600) that takes
// one command per line and answers one line. Used by tests and automation to
// blow wind and to ask what the display is doing. Commands:
//   gust SIDE [M/S]     a gust from left|right|front|back (default: [wind] gust_speed)
//   blowout [SIDE] [M/S] a strong gust that can blow candles out (default: front, 4x gust_speed)
//   wind X Z            set the steady wind (m/s; x: to the right, z: toward the viewer)
//   calm                steady wind 0
//   volume [0..1]       sets the master sound volume (glides, no click); alone: answers it
//   scene NAME|PATH     shows a built-in scene (e.g. eigen-fireplace) or a scene file;
//                       a broken one is refused and the running one stays
//   brightness [0..1]   the master brightness (glides); alone: answers it
//   screen [on|off]     switches the screen on or off; alone: answers it
//   reload              re-reads the --config file and the scene (as SIGHUP does)
//   schedule            what the [schedule] has on now and what comes next
//   state               one JSON line: step, frame, wind, events, scene, screen, fps, ...
//   ping                answers "pong"
//   help                lists the commands
// Wind and volume commands answer "ok"; mistakes answer "error: ..." and change nothing.
#pragma once

#include <poll.h>

#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "wind/wind_field.h"

namespace candela {

struct ControlCommand {
  enum class Kind {
    kWind,
    kVolume,
    kState,
    kPing,
    kHelp,
    // The kiosk's (input/kiosk_control.h):
    kScene,
    kBrightness,
    kScreen,
    kReload,
    kSchedule,
    kError
  } kind = Kind::kError;
  WindEvent event;
  float volume = -1.0f;  // kVolume, kBrightness: 0..1; below 0: the word alone (a question)
  int screen = -1;       // kScreen: 1 on, 0 off, -1 a question
  std::string scene;     // kScene: a built-in scene's name or a scene file's path
  std::string error;     // kError: what was wrong
};
ControlCommand parse_control_command(std::string_view line, const WindSpec& wind);
extern const char* const kControlHelp;

class ControlServer {
 public:
  // Creates the socket at `path`. A lock file beside it (`path`.lock, held
  // with flock for the server's life) tells a live server from a stale
  // socket: a second candela is refused and leaves the first one's socket
  // alone; a stale socket is replaced; never another kind of file.
  // Clients silent for `idle_timeout_ms` are dropped, and when all
  // kMaxClients slots are taken a new client replaces the longest-silent one,
  // so silent clients cannot lock everyone out. Throws RuntimeError saying
  // why the socket cannot be made.
  explicit ControlServer(std::string path, int64_t idle_timeout_ms = kIdleTimeoutMs);
  ~ControlServer();
  ControlServer(const ControlServer&) = delete;
  ControlServer& operator=(const ControlServer&) = delete;

  const std::string& path() const { return path_; }
  // Appends the listening socket and the clients to `fds`.
  void add_fds(std::vector<pollfd>& fds) const;
  // Serves what poll() reported in fds[0..n) (the entries add_fds appended);
  // `answer` turns one command line into one reply line (without '\n').
  void serve(const pollfd* fds, size_t n,
             const std::function<std::string(std::string_view)>& answer);
  // What an Answerer gives for one line: the reply now, or none yet
  // (`deferred`: work another thread does, such as loading a scene). A
  // deferred reply comes through complete() with the line's ticket; until
  // then that client's further lines wait (replies stay in order) and it is
  // not dropped as idle, while every other client is served.
  struct Answer {
    std::string reply;
    bool deferred = false;
  };
  using Answerer = std::function<Answer(std::string_view line, uint64_t ticket)>;
  void serve(const pollfd* fds, size_t n, const Answerer& answer);
  // The deferred reply to the line given `ticket` (on the serving thread):
  // sent, then that client's waiting lines are answered. Its client gone
  // since: nothing is sent.
  void complete(uint64_t ticket, const std::string& reply, const Answerer& answer);

  // Drops clients silent since before now_ns - idle timeout; returns when the
  // next one would time out (monotonic ns; INT64_MAX: no clients).
  int64_t expire_idle(int64_t now_ns);

  static constexpr size_t kMaxClients = 8;
  static constexpr size_t kMaxLine = 1024;
  static constexpr int64_t kIdleTimeoutMs =
      300'000;  // long-lived clients (a bridge) may ask rarely

 private:
  struct Client {
    int fd;
    std::string buffer;
    int64_t last_ns;       // when it connected or last sent something
    uint64_t waiting = 0;  // the ticket of its deferred reply; 0: none
  };
  void drop(size_t index);
  // Answers the client's complete lines until one is deferred; false: it
  // is to be dropped (a reply it does not read, a line too long).
  bool pump(Client& c, const Answerer& answer);
  uint64_t next_ticket_ = 0;
  std::string path_;
  int64_t idle_ns_;
  int listen_fd_ = -1;
  int lock_fd_ = -1;
  std::vector<Client> clients_;
};

}  // namespace candela
