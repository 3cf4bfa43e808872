// The whole `candela` program under live control (issue 16): scene swaps
// without a black frame, brightness, the screen switched off (no frames, no
// CPU) and on, reload and SIGHUP with systemd's RELOADING/READY, a schedule
// run on a shifted and sped-up clock, and journald priorities. Each case
// starts a headless candela with a control socket and talks to it.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "core/image.h"
#include "support/ask_line.h"
#include "support/program_command.h"

extern char** environ;

namespace candela {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

const std::string kBin = std::string(CANDELA_BINARY_DIR) + "/firmware/candela";
const std::string kScenes = std::string(CANDELA_SOURCE_DIR) + "/firmware/scenes";

class TempDir {
 public:
  TempDir() {
    std::string t = (fs::temp_directory_path() / "candela-live-XXXXXX").string();
    path_ = mkdtemp(t.data()) ? t : "";
  }
  ~TempDir() { fs::remove_all(path_); }
  std::string operator/(const std::string& name) const { return path_ + "/" + name; }

 private:
  std::string path_;
};

void write_file(const std::string& path, const std::string& text) {
  // Written beside and renamed: candela never reads half a file.
  std::ofstream(path + ".new") << text;
  fs::rename(path + ".new", path);
}

std::string read_file(const std::string& path) {
  std::ifstream f(path);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

double json_number(const std::string& json, const std::string& key) {
  std::smatch m;
  if (!std::regex_search(json, m, std::regex("\"" + key + "\":(-?[0-9.]+)"))) return NAN;
  return std::stod(m[1]);
}
std::string json_string(const std::string& json, const std::string& key) {
  std::smatch m;
  if (!std::regex_search(json, m, std::regex("\"" + key + "\":\"([^\"]*)\""))) return "<none>";
  return m[1];
}

// CPU seconds (user + system) a process has used, from /proc/PID/stat.
double cpu_seconds(pid_t pid) {
  const std::string s = read_file("/proc/" + std::to_string(pid) + "/stat");
  const size_t close_paren = s.rfind(')');
  std::istringstream in(s.substr(close_paren + 2));
  std::string field;
  unsigned long long utime = 0, stime = 0;
  for (int i = 3; i <= 15 && in >> field; ++i) {
    if (i == 14) utime = std::stoull(field);
    if (i == 15) stime = std::stoull(field);
  }
  return static_cast<double>(utime + stime) / static_cast<double>(sysconf(_SC_CLK_TCK));
}

// A measuring window: nothing to wait for, time itself is what is measured.
void measure_for(int ms) { poll(nullptr, 0, ms); }

// A running candela with a control socket, its stderr in a file.
class Candela {
 public:
  Candela(const TempDir& dir, std::vector<std::string> args, std::vector<std::string> env = {})
      : socket_(dir / "ctl"), log_(dir / "candela.log") {
    const std::vector<std::string> cmd = test::program_command(kBin);  // the emulator first, if any
    args.insert(args.begin(), cmd.begin(), cmd.end());
    for (const char* a : {"--control", socket_.c_str()}) args.emplace_back(a);
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    for (char** e = environ; *e; ++e) env.emplace_back(*e);
    std::vector<char*> envp;
    for (auto& e : env) envp.push_back(e.data());
    envp.push_back(nullptr);
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_addopen(&fa, 2, log_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (posix_spawn(&pid_, argv[0], &fa, nullptr, argv.data(), envp.data()) != 0) pid_ = -1;
    posix_spawn_file_actions_destroy(&fa);
  }
  ~Candela() {
    if (pid_ > 0) {
      kill(pid_, SIGKILL);
      waitpid(pid_, nullptr, 0);
    }
  }
  pid_t pid() const { return pid_; }
  std::string log() const { return read_file(log_); }

  // Connects (the socket appears once candela runs), bounded by `seconds`.
  bool connect_within(int seconds) {
    const auto deadline = Clock::now() + std::chrono::seconds(seconds);
    while (Clock::now() < deadline) {
      if (fs::exists(socket_)) {
        fd_ = socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
        sockaddr_un a{};
        a.sun_family = AF_UNIX;
        std::strncpy(a.sun_path, socket_.c_str(), sizeof a.sun_path - 1);
        if (connect(fd_, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0) {
          timeval tv{90, 0};  // a scene swap answers once built
          setsockopt(fd_, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
          return true;
        }
        close(fd_);
        fd_ = -1;
      }
      measure_for(10);  // polling for the socket to appear, bounded by the deadline
    }
    return false;
  }
  std::string ask(const std::string& line) { return test::ask_line(fd_, line); }
  // Asks `state` until `ok(state)` or `seconds` pass; returns the last state.
  template <typename F>
  std::string state_until(F ok, int seconds) {
    const auto deadline = Clock::now() + std::chrono::seconds(seconds);
    std::string s = ask("state");
    while (!ok(s) && Clock::now() < deadline) {
      measure_for(10);  // between questions; bounded by the deadline
      s = ask("state");
    }
    return s;
  }
  double frame() { return json_number(ask("state"), "frame"); }
  // SIGTERM and the exit status (0: a clean stop).
  int stop() {
    if (fd_ >= 0) close(fd_);
    fd_ = -1;
    kill(pid_, SIGTERM);
    int status = 0;
    waitpid(pid_, &status, 0);
    pid_ = -1;
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  }

 private:
  std::string socket_, log_;
  pid_t pid_ = -1;
  int fd_ = -1;
};

// Mean of all channels and the brightest channel value of a PNG frame.
struct FrameStats {
  double mean = 0;
  int max = 0;
};
FrameStats stats_of(const std::string& png) {
  const Image im = read_png(png, 3);
  FrameStats s;
  double sum = 0;
  for (uint8_t v : im.pixels) {
    sum += v;
    s.max = std::max<int>(s.max, v);
  }
  s.mean = sum / static_cast<double>(im.pixels.size());
  return s;
}
std::string frame_png(const std::string& dir, int n) {
  char name[32];
  std::snprintf(name, sizeof name, "/frame_%06d.png", n);
  return dir + name;
}

const std::vector<std::string> kHeadless = {
    "--display", "headless", "--size", "64x48", "--realtime", "--fps", "30", "--log-level", "info"};
std::vector<std::string> with(std::vector<std::string> a, const std::vector<std::string>& more) {
  a.insert(a.end(), more.begin(), more.end());
  return a;
}

// `scene NAME`: the new scene replaces the old between two frames, every
// frame written shows something (never black), a broken scene is refused
// with its error and the shown one stays.
TEST(LiveControl, SceneSwapsWithoutABlackFrame) {
  TempDir dir;
  const std::string out = dir / "frames";
  Candela c(dir, with(kHeadless, {"--test-pattern", "--out", out}));
  ASSERT_TRUE(c.connect_within(30)) << c.log();
  std::string s =
      c.state_until([](const std::string& st) { return json_number(st, "frame") >= 5; }, 30);
  EXPECT_EQ(json_string(s, "scene"), "test-pattern") << s;
  EXPECT_EQ(c.ask("scene default"), "ok");
  s = c.ask("state");
  EXPECT_EQ(json_string(s, "scene"), "default") << s;
  const double swapped_at = json_number(s, "frame");
  const std::string broken = dir / "broken.toml";
  write_file(broken, "[[element]]\nkind = \"candles\"\nbogus = 1\n");
  std::string r = c.ask("scene " + broken);
  EXPECT_EQ(r.rfind("error: " + broken + ": element[0]", 0), 0u) << r;
  EXPECT_NE(r.find("the running scene stays"), std::string::npos) << r;
  r = c.ask("scene nowhere");
  EXPECT_EQ(r.rfind("error: scene \"nowhere\": no such built-in scene", 0), 0u) << r;
  s = c.state_until(
      [&](const std::string& st) { return json_number(st, "frame") >= swapped_at + 45; }, 30);
  EXPECT_EQ(json_string(s, "scene"), "default") << s;
  EXPECT_EQ(c.stop(), 0) << c.log();
  // Every frame shows something: the test pattern, the cross-fade, the candles.
  int frames = 0;
  for (int i = 0; fs::exists(frame_png(out, i)); ++i, ++frames) {
    const FrameStats f = stats_of(frame_png(out, i));
    EXPECT_GT(f.max, 60) << "frame " << i << " is black (max " << f.max << ")";
  }
  ASSERT_GT(frames, swapped_at + 40);
  const FrameStats first = stats_of(frame_png(out, 2));
  const FrameStats last = stats_of(frame_png(out, frames - 1));
  EXPECT_GT(first.mean, 3 * last.mean) << "the bright test pattern became the dark candle scene";
  // The cross-fade: a frame after the swap lies between the two.
  const FrameStats mid = stats_of(frame_png(out, static_cast<int>(swapped_at) + 5));
  EXPECT_GT(mid.mean, last.mean * 1.2);
  EXPECT_LT(mid.mean, first.mean * 0.97);
}

// `brightness 0.25`: the frame is a quarter as bright within a quarter second.
TEST(LiveControl, BrightnessDimsTheFrames) {
  TempDir dir;
  const std::string out = dir / "frames";
  Candela c(dir, with(kHeadless, {"--test-pattern", "--out", out}));
  ASSERT_TRUE(c.connect_within(30)) << c.log();
  c.state_until([](const std::string& st) { return json_number(st, "frame") >= 3; }, 30);
  EXPECT_EQ(c.ask("brightness 0.25"), "ok");
  EXPECT_EQ(c.ask("brightness"), "0.250");
  const double at = c.frame();
  const std::string s =
      c.state_until([&](const std::string& st) { return json_number(st, "frame") >= at + 20; }, 30);
  EXPECT_NEAR(json_number(s, "brightness"), 0.25, 1e-6) << s;
  EXPECT_EQ(c.stop(), 0) << c.log();
  const double before = stats_of(frame_png(out, 1)).mean;
  const double after = stats_of(frame_png(out, static_cast<int>(at) + 12)).mean;  // 0.4 s later
  EXPECT_NEAR(after / before, 0.25, 0.03) << before << " -> " << after;
  // Dimmed, not see-through (issue 34): the frame's alpha is opaque (it was
  // 191 at brightness 0.5, and viewers showed washed-out frames).
  const Image dimmed = read_png(frame_png(out, static_cast<int>(at) + 12));
  ASSERT_EQ(dimmed.channels, 4);
  int see_through = 0;
  for (size_t i = 3; i < dimmed.pixels.size(); i += 4) see_through += dimmed.pixels[i] != 255;
  EXPECT_EQ(see_through, 0) << "pixels with alpha below 255 in a dimmed frame";
}

// `screen off`: no frame is drawn or presented and candela sleeps; `screen
// on` resumes where the animation was.
TEST(LiveControl, ScreenOffStopsFramesAndSleeps) {
  TempDir dir;
  // The built-in candles at 320x240: enough work that "on" shows on the CPU.
  Candela c(dir, {"--display", "headless", "--size", "320x240", "--realtime", "--fps", "30"});
  ASSERT_TRUE(c.connect_within(30)) << c.log();
  c.state_until([](const std::string& st) { return json_number(st, "frame") >= 10; }, 60);
  const double cpu_on0 = cpu_seconds(c.pid());
  measure_for(1000);
  const double cpu_on = cpu_seconds(c.pid()) - cpu_on0;
  EXPECT_EQ(c.ask("screen off"), "ok");
  EXPECT_EQ(c.ask("screen"), "off");
  const double f0 = c.frame();
  const double cpu0 = cpu_seconds(c.pid());
  measure_for(1500);
  const double cpu_off = cpu_seconds(c.pid()) - cpu0;
  const std::string s = c.ask("state");
  EXPECT_LE(json_number(s, "frame") - f0, 1) << "frames went on with the screen off: " << s;
  EXPECT_EQ(json_string(s, "screen"), "off") << s;
  EXPECT_EQ(json_number(s, "fps"), 0) << s;
  EXPECT_LT(cpu_off / 1.5, 0.02) << "CPU with the screen off: " << cpu_off / 1.5 * 100
                                 << "% (on: " << cpu_on * 100 << "%)";
  std::printf("[ figures ] CPU with the screen on: %.1f%%, off: %.2f%% of one core\n", cpu_on * 100,
              cpu_off / 1.5 * 100);
  EXPECT_EQ(c.ask("screen on"), "ok");
  const std::string on =
      c.state_until([&](const std::string& st) { return json_number(st, "frame") >= f0 + 10; }, 10);
  EXPECT_GE(json_number(on, "frame"), f0 + 10) << on;
  EXPECT_EQ(c.stop(), 0) << c.log();
}

// A datagram socket standing in for systemd's NOTIFY_SOCKET.
class NotifySocket {
 public:
  explicit NotifySocket(const std::string& path) : path_(path) {
    fd_ = socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0);
    sockaddr_un a{};
    a.sun_family = AF_UNIX;
    std::strncpy(a.sun_path, path.c_str(), sizeof a.sun_path - 1);
    bind(fd_, reinterpret_cast<sockaddr*>(&a), sizeof a);
  }
  ~NotifySocket() { close(fd_); }
  // The next message that contains `what` (others are skipped), or "" after `ms`.
  std::string next_with(const std::string& what, int ms) {
    const auto deadline = Clock::now() + std::chrono::milliseconds(ms);
    while (Clock::now() < deadline) {
      pollfd p{fd_, POLLIN, 0};
      const auto left =
          std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
      if (poll(&p, 1, static_cast<int>(std::max<long long>(1, left))) <= 0) continue;
      char buf[512];
      const ssize_t n = recv(fd_, buf, sizeof buf, 0);
      if (n <= 0) continue;
      const std::string m(buf, static_cast<size_t>(n));
      seen += m + "|";
      if (m.find(what) != std::string::npos) return m;
    }
    return "";
  }
  std::string seen;

 private:
  std::string path_;
  int fd_ = -1;
};

// SIGHUP and `reload` re-read the config and its scene; systemd hears
// RELOADING=1 then READY=1; a broken config is answered and changes nothing.
TEST(LiveControl, ReloadAndSighupRereadTheConfig) {
  TempDir dir;
  const std::string config = dir / "candela.toml";
  write_file(config, "scene = \"" + kScenes + "/test-pattern.toml\"\ndisplay = \"headless\"\n");
  NotifySocket notify(dir / "notify");
  Candela c(dir, {"--config", config, "--size", "64x48", "--realtime", "--fps", "30"},
            {"NOTIFY_SOCKET=" + (dir / "notify")});
  ASSERT_TRUE(c.connect_within(30)) << c.log();
  EXPECT_NE(notify.next_with("READY=1", 30'000), "") << notify.seen << c.log();
  EXPECT_EQ(json_string(c.ask("state"), "scene"), kScenes + "/test-pattern.toml");
  write_file(config, "scene = \"" + kScenes + "/default.toml\"\ndisplay = \"headless\"\n");
  kill(c.pid(), SIGHUP);
  const std::string reloading = notify.next_with("RELOADING=1", 30'000);
  EXPECT_NE(reloading.find("MONOTONIC_USEC="), std::string::npos) << notify.seen;
  EXPECT_EQ(notify.next_with("READY=1", 60'000), "READY=1") << notify.seen << c.log();
  EXPECT_EQ(json_string(c.ask("state"), "scene"), kScenes + "/default.toml");
  // systemctl status names the scene now shown (STATUS= about once a second),
  // and says when the screen is off rather than its last frame rate.
  EXPECT_NE(notify.next_with("STATUS=default.toml: ", 30'000), "") << notify.seen;
  EXPECT_EQ(c.ask("screen off"), "ok");
  EXPECT_EQ(notify.next_with("STATUS=default.toml: screen off", 30'000),
            "STATUS=default.toml: screen off")
      << notify.seen;
  EXPECT_EQ(c.ask("screen on"), "ok");
  EXPECT_NE(notify.next_with(" fps", 30'000), "") << notify.seen;
  write_file(config, "scene = 5\n");
  const std::string r = c.ask("reload");
  EXPECT_EQ(r, "error: " + config + ": scene: expected a string, got 5; the running settings stay")
      << r;
  EXPECT_EQ(json_string(c.ask("state"), "scene"), kScenes + "/default.toml");
  write_file(config, "scene = \"" + kScenes + "/test-pattern.toml\"\n");
  EXPECT_EQ(c.ask("reload"), "ok");
  EXPECT_EQ(json_string(c.ask("state"), "scene"), kScenes + "/test-pattern.toml");
  EXPECT_EQ(c.stop(), 0) << c.log();  // SIGTERM still ends it
  EXPECT_NE(c.log().find("SIGHUP: reloading"), std::string::npos) << c.log();
}

// A [schedule] on a clock started at Monday 06:59:00 (UTC) running 10x
// (6 s before 07:00: slow start-ups, sanitizers, included):
// off at first (no frame), on at 07:00, off again at 07:01 with the frame
// counter stopped, and `schedule` says what comes next.
TEST(LiveControl, ScheduleSwitchesTheScreenOnAFastClock) {
  TempDir dir;
  const std::string config = dir / "candela.toml";
  write_file(config, "scene = \"" + kScenes +
                         "/test-pattern.toml\"\ndisplay = \"headless\"\n[schedule]\n"
                         "mon = \"07:00-07:01\"\nfade_in = 0\nfade_out = 0\n");
  Candela c(dir,
            {"--config", config, "--size", "64x48", "--realtime", "--fps", "30", "--clock-start",
             "2026-12-07T06:59:00", "--clock-scale", "10"},
            {"TZ=UTC"});
  ASSERT_TRUE(c.connect_within(30)) << c.log();
  std::string s = c.ask("state");
  if (json_string(s, "screen") == "off") {
    EXPECT_EQ(json_number(s, "frame"), 0) << s;
  }
  const std::string first = c.ask("schedule");
  EXPECT_EQ(first.rfind("now mon 06:59: screen off", 0), 0u) << first;
  EXPECT_NE(first.find("next: on at mon 07:00"), std::string::npos) << first;
  s = c.state_until(
      [](const std::string& st) {
        return json_string(st, "screen") == "on" && json_number(st, "frame") > 10;
      },
      20);
  EXPECT_EQ(json_string(s, "screen"), "on") << s;
  EXPECT_NE(c.ask("schedule").find("next: off at mon 07:01"), std::string::npos);
  s = c.state_until([](const std::string& st) { return json_string(st, "screen") == "off"; }, 30);
  ASSERT_EQ(json_string(s, "screen"), "off") << s;
  const double f0 = c.frame();
  measure_for(600);
  EXPECT_LE(c.frame() - f0, 1) << "the frame counter ran on with the screen scheduled off";
  const std::string sched = c.ask("schedule");
  EXPECT_NE(sched.find("screen off"), std::string::npos) << sched;
  EXPECT_NE(sched.find("next: on at mon 07:00 (in 6d 23h)"), std::string::npos) << sched;
  EXPECT_EQ(c.stop(), 0) << c.log();
  EXPECT_NE(c.log().find("screen off (schedule)"), std::string::npos) << c.log();
}

// Under systemd (JOURNAL_STREAM names stderr) each line carries its syslog
// priority, so `journalctl -p warning` picks out warnings and errors;
// elsewhere the lines are plain.
TEST(LiveControl, JournalPriorities) {
  for (const bool journal : {true, false}) {
    TempDir dir;
    const std::string log = dir / "candela.log";
    const std::string scene = dir / "empty.toml";
    write_file(scene, "[wind]\n");  // no elements: a warning
    std::ofstream(log).close();
    struct stat st {};
    ASSERT_EQ(stat(log.c_str(), &st), 0);
    std::vector<std::string> env;
    if (journal)
      env.push_back("JOURNAL_STREAM=" + std::to_string(st.st_dev) + ":" +
                    std::to_string(st.st_ino));
    else
      env.push_back("JOURNAL_STREAM=1:2");  // someone else's stream
    Candela c(dir, {"--display", "headless", "--size", "32x24", "--scene", scene, "--frames", "3"},
              env);
    int status = 0;
    waitpid(c.pid(), &status, 0);
    const std::string text = c.log();
    const std::string p4 = journal ? "<4>" : "", p6 = journal ? "<6>" : "";
    EXPECT_NE(text.find(p4 + "candela: warn: "), std::string::npos) << text;
    EXPECT_NE(text.find(p6 + "candela: info: "), std::string::npos) << text;
    if (!journal) {
      EXPECT_EQ(text.find("<6>"), std::string::npos) << text;
    }
    std::istringstream lines(text);
    for (std::string line; std::getline(lines, line);)
      if (journal) {
        EXPECT_TRUE(std::regex_match(line, std::regex("<[3467]>candela: .*"))) << line;
      }
  }
}

}  // namespace
}  // namespace candela
