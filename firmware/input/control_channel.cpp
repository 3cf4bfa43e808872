#include "input/control_channel.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstdlib>
#include <cstring>

#include "core/error.h"
#include "core/log.h"
#include "input/input_event.h"

namespace candela {

const char* const kControlHelp =
    "commands: gust SIDE [M/S] | blowout [SIDE] [M/S] | wind X Z | calm | volume [0..1] | "
    "scene NAME|PATH | brightness [0..1] | screen [on|off] | reload | schedule | state | ping | "
    "help "
    "(SIDE: left right front back)";

namespace {

std::vector<std::string_view> split_words(std::string_view s) {
  std::vector<std::string_view> words;
  size_t i = 0;
  while (i < s.size()) {
    while (i < s.size() && (s[i] == ' ' || s[i] == '\t' || s[i] == '\r')) ++i;
    size_t j = i;
    while (j < s.size() && s[j] != ' ' && s[j] != '\t' && s[j] != '\r') ++j;
    if (j > i) words.push_back(s.substr(i, j - i));
    i = j;
  }
  return words;
}

// Plain decimal only: strtod would also take "0x10" (16), "inf" or "1e1".
// from_chars (general format) takes no hex; a leading '+' is allowed here.
bool parse_number(std::string_view w, double lo, double hi, double& out) {
  if (!w.empty() && w[0] == '+') w.remove_prefix(1);
  double v = 0;
  const auto r = std::from_chars(w.data(), w.data() + w.size(), v, std::chars_format::fixed);
  if (w.empty() || r.ec != std::errc() || r.ptr != w.data() + w.size() || !std::isfinite(v) ||
      v < lo || v > hi)
    return false;
  out = v;
  return true;
}

// Words echoed in errors are cut short.
std::string echo(std::string_view w) {
  return w.size() <= 40
             ? std::string(w)
             : std::string(w.substr(0, 40)) + "... (" + std::to_string(w.size()) + " characters)";
}

// Unit vector of where wind from `side` blows to.
bool side_direction(std::string_view side, Fixed& x, Fixed& z) {
  const Fixed one = Fixed::from_int(1);
  x = z = Fixed{};
  if (side == "left")
    x = one;
  else if (side == "right")
    x = -one;
  else if (side == "front")
    z = -one;
  else if (side == "back")
    z = one;
  else
    return false;
  return true;
}

ControlCommand error(std::string what) {
  ControlCommand c;
  c.kind = ControlCommand::Kind::kError;
  c.error = std::move(what);
  return c;
}

}  // namespace

ControlCommand parse_control_command(std::string_view line, const WindSpec& wind) {
  const auto w = split_words(line);
  ControlCommand c;
  if (w.empty()) return error("empty command; " + std::string(kControlHelp));
  const std::string_view verb = w[0];
  if (verb == "state" || verb == "ping" || verb == "help" || verb == "reload" ||
      verb == "schedule") {
    if (w.size() != 1) return error(echo(verb) + " takes no arguments");
    c.kind = verb == "state"      ? ControlCommand::Kind::kState
             : verb == "ping"     ? ControlCommand::Kind::kPing
             : verb == "reload"   ? ControlCommand::Kind::kReload
             : verb == "schedule" ? ControlCommand::Kind::kSchedule
                                  : ControlCommand::Kind::kHelp;
    return c;
  }
  if (verb == "volume" || verb == "brightness") {
    const bool vol = verb == "volume";
    c.kind = vol ? ControlCommand::Kind::kVolume : ControlCommand::Kind::kBrightness;
    double v = 0;
    if (w.size() == 1) return c;
    if (w.size() != 2 || !parse_number(w[1], 0, 1, v))
      return error(std::string(verb) + ": expected one level in [0, 1] " +
                   (vol ? "(0 silent, 1 full), e.g. \"volume 0.5\""
                        : "(0 black, 1 full), e.g. \"brightness 0.5\"") +
                   (w.size() == 2 ? ", got \"" + echo(w[1]) + "\"" : std::string()));
    c.volume = static_cast<float>(v);
    return c;
  }
  if (verb == "screen") {
    c.kind = ControlCommand::Kind::kScreen;
    if (w.size() == 1) return c;
    if (w.size() != 2 || (w[1] != "on" && w[1] != "off"))
      return error("screen: expected on or off, e.g. \"screen off\"" +
                   (w.size() == 2 ? ", got \"" + echo(w[1]) + "\"" : std::string()));
    c.screen = w[1] == "on" ? 1 : 0;
    return c;
  }
  if (verb == "scene") {
    // The rest of the line, trimmed: a path may hold spaces.
    std::string_view rest = line.substr(line.find("scene") + 5);
    while (!rest.empty() && (rest.front() == ' ' || rest.front() == '\t')) rest.remove_prefix(1);
    while (!rest.empty() && (rest.back() == ' ' || rest.back() == '\t' || rest.back() == '\r'))
      rest.remove_suffix(1);
    if (rest.empty())
      return error(
          "scene: expected a built-in scene's name (e.g. \"scene eigen-fireplace\") or a scene "
          "file's path");
    c.kind = ControlCommand::Kind::kScene;
    c.scene = std::string(rest);
    return c;
  }
  c.kind = ControlCommand::Kind::kWind;
  if (verb == "gust" || verb == "blowout") {
    const bool blow = verb == "blowout";
    size_t i = 1;
    Fixed x, z;
    if (i < w.size() && side_direction(w[i], x, z)) {
      ++i;
    } else if (!blow) {
      return error("gust: expected a side (left, right, front, back), e.g. \"gust left 2.0\"");
    } else {
      side_direction("front", x, z);
    }
    double strength = (blow ? wind.gust_speed * 4 : wind.gust_speed).to_double();
    if (i < w.size() && !parse_number(w[i++], 0, 60, strength))
      return error(std::string(verb) + ": expected a speed in m/s in [0, 60], got \"" +
                   echo(w[i - 1]) + "\"");
    if (i < w.size()) return error(std::string(verb) + ": too many arguments");
    const Fixed s = Fixed::from_double(strength);
    c.event = {blow ? WindEvent::Type::kBlowOut : WindEvent::Type::kGust, x * s, z * s};
    return c;
  }
  if (verb == "wind") {
    double x = 0, z = 0;
    if (w.size() != 3 || !parse_number(w[1], -30, 30, x) || !parse_number(w[2], -30, 30, z))
      return error("wind: expected two speeds in m/s in [-30, 30], e.g. \"wind 0.5 0\"");
    c.event = {WindEvent::Type::kSteady, Fixed::from_double(x), Fixed::from_double(z)};
    return c;
  }
  if (verb == "calm") {
    if (w.size() != 1) return error("calm takes no arguments");
    c.event = {WindEvent::Type::kSteady, {}, {}};
    return c;
  }
  return error("unknown command \"" + echo(verb) + "\"; " + kControlHelp);
}

ControlServer::ControlServer(std::string path, int64_t idle_timeout_ms)
    : path_(std::move(path)), idle_ns_(idle_timeout_ms * 1'000'000) {
  sockaddr_un addr{};
  addr.sun_family = AF_UNIX;
  if (path_.empty() || path_.size() >= sizeof addr.sun_path)
    throw RuntimeError("control socket " + path_ + ": path empty or longer than " +
                       std::to_string(sizeof addr.sun_path - 1) + " bytes");
  // Something else at the path (a folder, a file) is refused before
  // anything is created beside it (`--control /tmp` made /tmp.lock).
  struct stat existing {};
  if (path_.back() == '/' || (lstat(path_.c_str(), &existing) == 0 && !S_ISSOCK(existing.st_mode)))
    throw RuntimeError("control socket " + path_ +
                       ": exists and is not a socket (expected a new path, e.g. "
                       "/run/candela/candela.sock); not replacing it");
  // The lock first: whoever holds it owns the socket path. The lock file is
  // never removed (removing it would let two servers lock different files).
  const std::string lock_path = path_ + ".lock";
  lock_fd_ = ::open(lock_path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0600);
  if (lock_fd_ < 0)
    throw RuntimeError("control socket " + path_ + ": cannot open its lock file " + lock_path +
                       ": " + std::strerror(errno));
  if (flock(lock_fd_, LOCK_EX | LOCK_NB) != 0) {
    const int err = errno;
    close(lock_fd_);
    lock_fd_ = -1;
    throw RuntimeError("control socket " + path_ +
                       (err == EWOULDBLOCK
                            ? std::string(": another candela is serving it (") + lock_path +
                                  " is locked); not taking it over"
                            : ": cannot lock " + lock_path + ": " + std::strerror(err)));
  }
  auto fail = [&](const std::string& why) {
    if (listen_fd_ >= 0) close(listen_fd_);
    listen_fd_ = -1;
    close(lock_fd_);
    lock_fd_ = -1;
    throw RuntimeError("control socket " + path_ + ": " + why);
  };
  struct stat st {};
  if (lstat(path_.c_str(), &st) == 0) {
    if (!S_ISSOCK(st.st_mode)) fail("exists and is not a socket; not replacing it");
    unlink(path_.c_str());  // stale: its server no longer holds the lock
  }
  listen_fd_ = socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
  if (listen_fd_ < 0) fail(std::strerror(errno));
  // Bind inside a private 0700 folder, tighten to 0600, then rename into
  // place: nobody else can ever connect in between (no umask games, which
  // would touch every thread).
  std::string dir = path_;
  dir = dir.substr(0, dir.find_last_of('/') == std::string::npos ? 0 : dir.find_last_of('/') + 1);
  std::string tmpl = (dir.empty() ? std::string("./") : dir) + ".candela-ctl-XXXXXX";
  const std::string tmp_dir = mkdtemp(tmpl.data()) ? tmpl : std::string();
  if (tmp_dir.empty())
    fail(std::string("cannot create a folder beside it: ") + std::strerror(errno));
  const std::string tmp_path = tmp_dir + "/s";
  std::strncpy(addr.sun_path, tmp_path.c_str(), sizeof addr.sun_path - 1);
  int err = 0;
  if (tmp_path.size() >= sizeof addr.sun_path)
    err = ENAMETOOLONG;
  else if (bind(listen_fd_, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0 ||
           chmod(tmp_path.c_str(), 0600) != 0 || listen(listen_fd_, 4) != 0 ||
           rename(tmp_path.c_str(), path_.c_str()) != 0)
    err = errno;
  unlink(tmp_path.c_str());
  rmdir(tmp_dir.c_str());
  if (err) fail(std::strerror(err));
  LOG_INFO("control socket: %s", path_.c_str());
}

ControlServer::~ControlServer() {
  for (auto& c : clients_) close(c.fd);
  if (listen_fd_ >= 0) {
    close(listen_fd_);
    unlink(path_.c_str());  // ours: we hold the lock
  }
  if (lock_fd_ >= 0) close(lock_fd_);
}

int64_t ControlServer::expire_idle(int64_t now) {
  int64_t next = INT64_MAX;
  for (size_t i = clients_.size(); i-- > 0;) {
    if (clients_[i].waiting) continue;  // silent because it waits on us
    const int64_t due = clients_[i].last_ns + idle_ns_;
    if (due <= now) {
      const char msg[] = "error: idle for too long; closing\n";
      (void)send(clients_[i].fd, msg, sizeof msg - 1, MSG_NOSIGNAL | MSG_DONTWAIT);
      drop(i);
    } else {
      next = std::min(next, due);
    }
  }
  return next;
}

void ControlServer::add_fds(std::vector<pollfd>& fds) const {
  fds.push_back({listen_fd_, POLLIN, 0});  // when full, a newcomer replaces the most idle
  for (const auto& c : clients_) fds.push_back({c.fd, POLLIN, 0});
}

void ControlServer::drop(size_t index) {
  close(clients_[index].fd);
  clients_.erase(clients_.begin() + static_cast<std::ptrdiff_t>(index));
}

void ControlServer::serve(const pollfd* fds, size_t n,
                          const std::function<std::string(std::string_view)>& answer) {
  serve(fds, n, [&](std::string_view line, uint64_t) { return Answer{answer(line)}; });
}

bool ControlServer::pump(Client& c, const Answerer& answer) {
  size_t nl;
  while (!c.waiting && (nl = c.buffer.find('\n')) != std::string::npos) {
    const uint64_t ticket = ++next_ticket_;
    Answer a = answer(std::string_view(c.buffer).substr(0, nl), ticket);
    c.buffer.erase(0, nl + 1);
    if (a.deferred) {
      c.waiting = ticket;
      break;
    }
    a.reply += '\n';
    // Replies are short; a client that does not read them is dropped.
    if (send(c.fd, a.reply.data(), a.reply.size(), MSG_NOSIGNAL | MSG_DONTWAIT) !=
        static_cast<ssize_t>(a.reply.size()))
      return false;
  }
  // A line longer than the limit; or, while a reply is awaited, more lines
  // queued than a few (a client cannot fill memory meanwhile).
  if (c.buffer.size() > (c.waiting ? 4 * kMaxLine : kMaxLine)) {
    const char msg[] = "error: line too long\n";
    (void)send(c.fd, msg, sizeof msg - 1, MSG_NOSIGNAL | MSG_DONTWAIT);
    return false;
  }
  return true;
}

void ControlServer::complete(uint64_t ticket, const std::string& reply, const Answerer& answer) {
  for (size_t i = 0; i < clients_.size(); ++i) {
    Client& c = clients_[i];
    if (c.waiting != ticket) continue;
    c.waiting = 0;
    c.last_ns = monotonic_ns();
    const std::string line = reply + '\n';
    if (send(c.fd, line.data(), line.size(), MSG_NOSIGNAL | MSG_DONTWAIT) !=
            static_cast<ssize_t>(line.size()) ||
        !pump(c, answer))
      drop(i);
    return;
  }
}

void ControlServer::serve(const pollfd* fds, size_t n, const Answerer& answer) {
  if (n == 0) return;
  // Clients first (fds[1..] match clients_ as add_fds listed them), newest last.
  std::vector<size_t> gone;
  for (size_t i = 1; i < n && i - 1 < clients_.size(); ++i) {
    if (!fds[i].revents) continue;
    Client& c = clients_[i - 1];
    char buf[512];
    const ssize_t got = recv(c.fd, buf, sizeof buf, MSG_DONTWAIT);
    if (got == 0 || (got < 0 && errno != EAGAIN && errno != EINTR)) {
      gone.push_back(i - 1);
      continue;
    }
    if (got < 0) continue;
    c.last_ns = monotonic_ns();
    c.buffer.append(buf, static_cast<size_t>(got));
    if (!pump(c, answer)) gone.push_back(i - 1);
  }
  for (size_t k = gone.size(); k-- > 0;) drop(gone[k]);
  if (fds[0].revents & POLLIN) {
    for (;;) {
      const int fd = accept4(listen_fd_, nullptr, nullptr, SOCK_CLOEXEC | SOCK_NONBLOCK);
      if (fd < 0) break;
      if (clients_.size() >= kMaxClients) {
        size_t idlest = 0;
        for (size_t i = 1; i < clients_.size(); ++i)
          if (clients_[i].last_ns < clients_[idlest].last_ns) idlest = i;
        const char msg[] = "error: too many clients; closing the most idle\n";
        (void)send(clients_[idlest].fd, msg, sizeof msg - 1, MSG_NOSIGNAL | MSG_DONTWAIT);
        drop(idlest);
      }
      clients_.push_back({fd, {}, monotonic_ns(), 0});
    }
  }
}

}  // namespace candela
