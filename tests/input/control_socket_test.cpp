// The control channel through a real UNIX socket: permissions, commands that
// reach the wind field, state replies, mistakes answered without effect; and
// the whole `candela` program driven through --control.
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
#include <condition_variable>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <regex>
#include <string>

#include "core/error.h"
#include "input/control_channel.h"
#include "input/input_event.h"
#include "input/input_hub.h"
#include "input/kiosk_control.h"
#include "scene/element.h"
#include "support/ask_line.h"
#include "support/program_command.h"

extern char** environ;

namespace candela {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

std::string temp_dir() {
  std::string t = (fs::temp_directory_path() / "candela-ctl-test-XXXXXX").string();
  EXPECT_NE(mkdtemp(t.data()), nullptr);
  return t;
}

// A client that sends a line and waits (with a deadline) for one reply line.
class Client {
 public:
  explicit Client(const std::string& path) {
    fd_ = socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
    sockaddr_un a{};
    a.sun_family = AF_UNIX;
    std::strncpy(a.sun_path, path.c_str(), sizeof a.sun_path - 1);
    connected_ = connect(fd_, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0;
    timeval tv{5, 0};
    setsockopt(fd_, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
  }
  ~Client() { close(fd_); }
  bool connected() const { return connected_; }
  int fd() const { return fd_; }
  std::string ask(const std::string& line) { return test::ask_line(fd_, line); }

 private:
  int fd_ = -1;
  bool connected_ = false;
};

double json_number(const std::string& json, const std::string& key) {
  std::smatch m;
  if (!std::regex_search(json, m, std::regex("\"" + key + "\":(-?[0-9.]+)"))) return NAN;
  return std::stod(m[1]);
}

TEST(ControlCommands, Parse) {
  WindSpec w;  // gust_speed 2
  auto c = parse_control_command("gust left 2.5", w);
  ASSERT_EQ(c.kind, ControlCommand::Kind::kWind);
  EXPECT_EQ(c.event.type, WindEvent::Type::kGust);
  EXPECT_EQ(c.event.x, Fixed::from_ratio(5, 2));
  c = parse_control_command("gust front", w);
  EXPECT_EQ(c.event.z, Fixed::from_int(-2));
  c = parse_control_command("  wind -0.5   0.25 ", w);
  ASSERT_EQ(c.kind, ControlCommand::Kind::kWind);
  EXPECT_EQ(c.event.type, WindEvent::Type::kSteady);
  EXPECT_EQ(c.event.x, -Fixed::from_ratio(1, 2));
  EXPECT_EQ(c.event.z, Fixed::from_ratio(1, 4));
  c = parse_control_command("blowout", w);
  EXPECT_EQ(c.event.type, WindEvent::Type::kBlowOut);
  EXPECT_EQ(c.event.z, Fixed::from_int(-8));
  c = parse_control_command("blowout left 10", w);
  EXPECT_EQ(c.event.x, Fixed::from_int(10));
  EXPECT_EQ(parse_control_command("state", w).kind, ControlCommand::Kind::kState);
  for (const char* bad : {"", "gust", "gust up", "gust left fast", "gust left 99", "wind 1",
                          "wind nan 0", "state now", "dance", "gust left 1 2", "wind 0x10 0",
                          "wind 1e1 0", "wind inf 0", "gust left 0x2", "wind 1. 0x"}) {
    c = parse_control_command(bad, w);
    EXPECT_EQ(c.kind, ControlCommand::Kind::kError) << bad;
    EXPECT_FALSE(c.error.empty()) << bad;
  }
}

// `volume`: a level in [0, 1], plain decimal; alone it is a question.
TEST(ControlCommands, Volume) {
  WindSpec w;
  auto c = parse_control_command("volume 0.25", w);
  ASSERT_EQ(c.kind, ControlCommand::Kind::kVolume);
  EXPECT_FLOAT_EQ(c.volume, 0.25f);
  c = parse_control_command("volume 1", w);
  EXPECT_FLOAT_EQ(c.volume, 1.0f);
  c = parse_control_command("  volume   0 ", w);
  ASSERT_EQ(c.kind, ControlCommand::Kind::kVolume);
  EXPECT_EQ(c.volume, 0.0f);
  c = parse_control_command("volume", w);
  ASSERT_EQ(c.kind, ControlCommand::Kind::kVolume);
  EXPECT_LT(c.volume, 0.0f);
  for (const char* bad : {"volume 1.01", "volume -0.1", "volume loud", "volume 0.5 0.5",
                          "volume 0x1", "volume nan", "volume 1e-1", "volume inf"}) {
    c = parse_control_command(bad, w);
    EXPECT_EQ(c.kind, ControlCommand::Kind::kError) << bad;
    EXPECT_NE(c.error.find("[0, 1]"), std::string::npos) << bad << ": " << c.error;
  }
  c = parse_control_command("volume " + std::string(900, '5'), w);
  ASSERT_EQ(c.kind, ControlCommand::Kind::kError);
  EXPECT_LT(c.error.size(), 200u) << c.error;
}

// Through the hub: `volume` sets what the frame loop hands the sound, and
// `state` reports it; a refused level changes nothing.
TEST(ControlSocket, VolumeIsSetAndReported) {
  InputHub hub({}, WindSpec{});
  hub.set_volume(0.6f);
  EXPECT_EQ(hub.answer("volume"), "0.600");
  EXPECT_EQ(hub.answer("volume 0.3"), "ok");
  EXPECT_FLOAT_EQ(hub.volume(), 0.3f);
  EXPECT_EQ(hub.answer("volume 3").rfind("error: volume:", 0), 0u);
  EXPECT_FLOAT_EQ(hub.volume(), 0.3f);
  EXPECT_NEAR(json_number(hub.state_json(), "volume"), 0.3, 1e-6);
  EXPECT_EQ(hub.answer("volume 0", InputHub::Origin::kMqtt), "ok");
  EXPECT_NEAR(json_number(hub.summary_json(), "volume"), 0.0, 1e-6);
}

// The window's keys take the road every input takes: queued by the hub,
// applied by drain(), counted as events (not as control events); quit and
// other keys blow nothing.
TEST(InputHubKeys, KeysBecomeWindEvents) {
  InputHub hub({}, WindSpec{});
  WindField wind;
  hub.on_key(Key::kQuit);
  hub.on_key(Key::kOther);
  hub.drain(wind);
  EXPECT_EQ(hub.events_applied(), 0u);
  EXPECT_EQ(wind.active_gusts(), 0);
  hub.on_key(Key::kLeft);
  hub.on_key(Key::kBlowOut);
  EXPECT_EQ(wind.active_gusts(), 0);  // nothing until the frame loop drains
  hub.drain(wind);
  EXPECT_EQ(hub.events_applied(), 2u);
  EXPECT_EQ(wind.active_gusts(), 2);
  EXPECT_NEAR(json_number(hub.state_json(), "control_events"), 0, 1e-9);
}

// Issue 15 (12): strtod took "0x10" as 16; and a long bad word is not echoed whole.
TEST(ControlCommands, OnlyPlainDecimalNumbers) {
  WindSpec w;
  auto c = parse_control_command("wind 0x10 0", w);
  EXPECT_EQ(c.kind, ControlCommand::Kind::kError);
  c = parse_control_command("wind +1.5 -0.5", w);
  ASSERT_EQ(c.kind, ControlCommand::Kind::kWind);
  EXPECT_EQ(c.event.x, Fixed::from_ratio(3, 2));
  c = parse_control_command("gust left " + std::string(900, '9'), w);
  ASSERT_EQ(c.kind, ControlCommand::Kind::kError);
  EXPECT_LT(c.error.size(), 200u) << c.error;
  c = parse_control_command(std::string(900, 'x'), w);
  EXPECT_LT(c.error.size(), 300u) << c.error;
}

TEST(ControlSocket, StateReportsCandlesLit) {
  const std::string dir = temp_dir();
  InputHub hub({}, WindSpec{}, dir + "/ctl");
  hub.start();
  Client client(dir + "/ctl");
  ASSERT_TRUE(client.connected());
  EXPECT_NE(client.ask("state").find("\"candles_lit\":null"), std::string::npos);  // no candles
  hub.publish(1, 1, WindSample{}, 5);
  EXPECT_EQ(json_number(client.ask("state"), "candles_lit"), 5);
  hub.stop();
  fs::remove_all(dir);
}

// Issue 15 (9): a second instance used to take a live socket over (and delete it on exit).
TEST(ControlSocket, ASecondServerCannotStealALiveSocket) {
  const std::string dir = temp_dir();
  const std::string path = dir + "/ctl";
  {
    ControlServer first(path);
    try {
      ControlServer second(path);
      ADD_FAILURE() << "a second server took the socket";
    } catch (const RuntimeError& e) {
      EXPECT_NE(std::string(e.what()).find("another candela is serving it"), std::string::npos)
          << e.what();
    }
    // The first one's socket is still there and still answers.
    Client c(path);
    EXPECT_TRUE(c.connected());
  }
  EXPECT_FALSE(fs::exists(path));
  // A socket left by a server that died (no lock held) is stale: replaced.
  {
    const int fd = socket(AF_UNIX, SOCK_STREAM, 0);
    sockaddr_un a{};
    a.sun_family = AF_UNIX;
    std::strncpy(a.sun_path, path.c_str(), sizeof a.sun_path - 1);
    ASSERT_EQ(bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a), 0);
    close(fd);
  }
  ASSERT_TRUE(fs::exists(path));
  EXPECT_NO_THROW(ControlServer again(path));
  fs::remove_all(dir);
}

// Issue 15 (9): eight silent clients used to lock everyone out.
TEST(ControlSocket, SilentClientsCannotLockEveryoneOut) {
  const std::string dir = temp_dir();
  InputHub hub({}, WindSpec{}, dir + "/ctl");
  hub.start();
  std::vector<std::unique_ptr<Client>> silent;
  for (size_t i = 0; i < ControlServer::kMaxClients; ++i) {
    silent.push_back(std::make_unique<Client>(dir + "/ctl"));
    ASSERT_TRUE(silent.back()->connected());
  }
  Client late(dir + "/ctl");
  ASSERT_TRUE(late.connected());
  EXPECT_EQ(late.ask("ping"), "pong");  // before: no reply (never accepted)
  hub.stop();
  fs::remove_all(dir);
}

// A kiosk whose scene loads take as long as the test says (KioskControl is
// the interface the runtime's Kiosk implements): `scene` waits until
// release() or 10 s; other commands answer at once.
class SlowSceneKiosk final : public KioskControl {
 public:
  std::string command(const ControlCommand& c) override {
    if (c.kind != ControlCommand::Kind::kScene) return "ok";
    std::unique_lock lock(mu_);
    started_ = true;
    cv_.notify_all();
    const bool released = cv_.wait_for(lock, std::chrono::seconds(10), [&] { return released_; });
    return released ? "ok" : "error: never released";
  }
  KioskStatus status() const override { return {}; }
  void wait_started() {
    std::unique_lock lock(mu_);
    cv_.wait_for(lock, std::chrono::seconds(10), [&] { return started_; });
  }
  void release() {
    std::lock_guard lock(mu_);
    released_ = true;
    cv_.notify_all();
  }

 private:
  std::mutex mu_;
  std::condition_variable cv_;
  bool started_ = false, released_ = false;
};

// Issue 34: a scene load (up to a minute: a model, a story planned, the
// frame loop's build) ran on the input thread, so GPIO and every other
// control client waited for it. Now it runs beside: another client is
// answered while it loads, and its own client gets the reply when it is
// done, its next line after it, in order.
TEST(ControlSocket, AnotherClientIsServedWhileASceneLoads) {
  const std::string dir = temp_dir();
  SlowSceneKiosk kiosk;
  InputHub hub({}, WindSpec{}, dir + "/ctl");
  hub.set_kiosk(&kiosk);
  hub.start();
  Client loader(dir + "/ctl"), other(dir + "/ctl");
  ASSERT_TRUE(loader.connected());
  ASSERT_TRUE(other.connected());
  const std::string lines = "scene eigen-fireplace\nping\n";
  ASSERT_EQ(send(loader.fd(), lines.data(), lines.size(), MSG_NOSIGNAL),
            static_cast<ssize_t>(lines.size()));
  kiosk.wait_started();
  // Before: no reply until the scene was done (5 s receive timeout).
  EXPECT_EQ(other.ask("ping"), "pong") << "served while the scene loads";
  EXPECT_EQ(other.ask("volume 0.2"), "ok");
  pollfd p{loader.fd(), POLLIN, 0};
  EXPECT_EQ(poll(&p, 1, 0), 0) << "the loading client has no reply yet";
  kiosk.release();
  char buf[64];
  std::string got;
  while (got.size() < std::strlen("ok\npong\n")) {
    const ssize_t n = recv(loader.fd(), buf, sizeof buf, 0);
    if (n <= 0) break;
    got.append(buf, static_cast<size_t>(n));
  }
  EXPECT_EQ(got, "ok\npong\n") << "the scene's reply, then its next line's, in order";
  hub.stop();
  fs::remove_all(dir);
}

TEST(ControlSocket, IdleClientsTimeOut) {
  const std::string dir = temp_dir();
  ControlServer server(dir + "/ctl", 100);
  Client idle(dir + "/ctl");
  ASSERT_TRUE(idle.connected());
  std::vector<pollfd> fds;
  const auto deadline = Clock::now() + std::chrono::seconds(10);
  std::string said;
  // Serve until the server closes the silent client (reading what it says).
  for (bool closed = false; !closed && Clock::now() < deadline;) {
    fds.clear();
    server.add_fds(fds);
    poll(fds.data(), fds.size(), 20);
    server.serve(fds.data(), fds.size(), [](std::string_view) { return std::string("ok"); });
    server.expire_idle(monotonic_ns());
    char buf[128];
    const ssize_t n = recv(idle.fd(), buf, sizeof buf, MSG_DONTWAIT);
    if (n > 0) said.append(buf, static_cast<size_t>(n));
    closed = n == 0;
  }
  EXPECT_EQ(said, "error: idle for too long; closing\n");
  fs::remove_all(dir);
}

TEST(ControlSocket, RoundTripReachesTheWindField) {
  const std::string dir = temp_dir();
  const std::string path = dir + "/ctl";
  WindSpec spec;
  // Wind starts at the sampled point itself: no travel delay to wait for.
  spec.plane_distance = Fixed{};
  InputHub hub({}, spec, path);
  hub.start();
  ASSERT_TRUE(hub.control_ready());
  struct stat st {};
  ASSERT_EQ(stat(path.c_str(), &st), 0);
  EXPECT_TRUE(S_ISSOCK(st.st_mode));
  EXPECT_EQ(st.st_mode & 0777, 0600u);
  // No leftovers of the private bind folder beside it; only its lock file.
  size_t entries = 0;
  for (const auto& e : fs::directory_iterator(dir))
    entries += e.path().filename() != "ctl" && e.path().filename() != "ctl.lock";
  EXPECT_EQ(entries, 0u);

  Client client(path);
  ASSERT_TRUE(client.connected());
  EXPECT_EQ(client.ask("ping"), "pong");
  EXPECT_EQ(client.ask("gust left 2.0"), "ok");
  EXPECT_EQ(client.ask("wind 0.5 -0.25"), "ok");
  EXPECT_EQ(client.ask("wind 0.5").rfind("error: ", 0), 0u);

  WindField wind(spec);
  hub.drain(wind);  // both events were queued before the replies came back
  EXPECT_EQ(hub.events_applied(), 2u);
  StepContext step;
  step.dt = Fixed::from_ratio(1, 60);
  for (int i = 0; i < 10; ++i) wind.update(step);
  const WindSample s = wind.sample(Vec3{});
  EXPECT_GT(s.x, Fixed::from_ratio(1, 2));  // steady 0.5 plus the rising gust
  EXPECT_EQ(s.z, -Fixed::from_ratio(1, 4));
  hub.publish(10, 5, s);

  const std::string state = client.ask("state");
  EXPECT_EQ(state.front(), '{');
  EXPECT_EQ(state.back(), '}');
  EXPECT_EQ(json_number(state, "events"), 2);
  EXPECT_EQ(json_number(state, "step"), 10);
  EXPECT_NEAR(json_number(state, "x"), s.x.to_double(), 1e-3);
  EXPECT_GE(json_number(state, "last"), 0);  // command -> wind field latency, ms

  // A second client at the same time is served too.
  Client other(path);
  ASSERT_TRUE(other.connected());
  EXPECT_EQ(other.ask("ping"), "pong");
  hub.stop();
  EXPECT_FALSE(fs::exists(path));  // removed on exit
  fs::remove_all(dir);
}

TEST(ControlSocket, RefusesToReplaceAFileThatIsNotASocket) {
  const std::string dir = temp_dir();
  const std::string path = dir + "/precious.txt";
  {
    std::FILE* f = std::fopen(path.c_str(), "w");
    std::fputs("keep me", f);
    std::fclose(f);
  }
  InputHub hub({}, WindSpec{}, path);
  hub.start();  // logs, runs without a control channel
  EXPECT_FALSE(hub.control_ready());
  EXPECT_EQ(fs::file_size(path), 7u);
  EXPECT_FALSE(fs::exists(path + ".lock")) << "nothing is created beside what is refused";
  fs::remove_all(dir);
}

// Issue 34: `--control /tmp` made /tmp.lock before finding /tmp no socket.
TEST(ControlSocket, AFolderIsRefusedAndNothingIsCreatedBesideIt) {
  const std::string dir = temp_dir();
  fs::create_directory(dir + "/sub");
  for (const std::string& path : {dir + "/sub", dir + "/sub/"}) {
    InputHub hub({}, WindSpec{}, path);
    hub.start();
    EXPECT_FALSE(hub.control_ready()) << path;
  }
  EXPECT_FALSE(fs::exists(dir + "/sub.lock"));
  EXPECT_FALSE(fs::exists(dir + "/sub/.lock"));
  EXPECT_TRUE(fs::is_empty(dir + "/sub"));
  fs::remove_all(dir);
}

// The real program: headless candela with --control answers `state`, and a
// gust sent through the socket shows in the wind it reports.
TEST(ControlSocket, CandelaProgramRegistersAGust) {
  const std::string dir = temp_dir();
  const std::string path = dir + "/ctl";
  const std::string bin = std::string(CANDELA_BINARY_DIR) + "/firmware/candela";
  // --realtime: animation time follows the clock, as on a screen. Free-running,
  // the test pattern takes thousands of steps a second and a gust is over
  // between two `state` questions.
  std::vector<std::string> args = test::program_command(bin);  // the emulator first, if any
  for (const char* a : {"--display", "headless", "--test-pattern", "--size", "64x48", "--realtime",
                        "--control", path.c_str(), "--log-level", "warn"})
    args.emplace_back(a);
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  ASSERT_EQ(posix_spawn(&pid, argv[0], nullptr, nullptr, argv.data(), environ), 0);
  const auto deadline = Clock::now() + std::chrono::seconds(20);
  std::unique_ptr<Client> client;
  while (Clock::now() < deadline) {
    if (fs::exists(path)) {
      client = std::make_unique<Client>(path);
      if (client->connected()) break;
    }
    usleep(10000);  // polling for the socket to appear, bounded by the deadline
  }
  ASSERT_TRUE(client && client->connected()) << "no control socket within 20 s";
  std::string state = client->ask("state");
  EXPECT_EQ(json_number(state, "x"), 0) << state;
  EXPECT_EQ(client->ask("gust right 3"), "ok");
  double x = 0;
  while (Clock::now() < deadline && !(x < -0.5)) {
    state = client->ask("state");
    x = json_number(state, "x");
  }
  EXPECT_LT(x, -0.5) << "the gust from the right never showed: " << state;
  EXPECT_EQ(json_number(state, "control_events"), 1) << state;
  kill(pid, SIGTERM);
  int status = 0;
  waitpid(pid, &status, 0);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << status;
  EXPECT_FALSE(fs::exists(path));
  fs::remove_all(dir);
}

// Issue 15 (12): `state` said "candles_lit": null whatever the scene showed.
// The built-in scene's seven candles are counted, and a blowout puts some out.
TEST(ControlSocket, CandelaProgramCountsCandlesLit) {
  const std::string dir = temp_dir();
  const std::string path = dir + "/ctl";
  const std::string bin = std::string(CANDELA_BINARY_DIR) + "/firmware/candela";
  std::vector<std::string> args = test::program_command(bin);  // the emulator first, if any
  for (const char* a : {"--display", "headless", "--size", "64x48", "--control", path.c_str(),
                        "--log-level", "warn"})
    args.emplace_back(a);
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  ASSERT_EQ(posix_spawn(&pid, argv[0], nullptr, nullptr, argv.data(), environ), 0);
  const auto deadline = Clock::now() + std::chrono::seconds(60);
  std::unique_ptr<Client> client;
  double lit = NAN;
  while (Clock::now() < deadline && !(lit >= 0)) {
    if (!client && fs::exists(path)) {
      client = std::make_unique<Client>(path);
      if (!client->connected()) client.reset();
    }
    if (client) lit = json_number(client->ask("state"), "candles_lit");  // null until drawn
    usleep(10000);  // polling for the first frame, bounded by the deadline
  }
  EXPECT_EQ(lit, 7) << "the built-in scene has seven candles, all lit at first";
  if (client) {
    EXPECT_EQ(client->ask("blowout front 30"), "ok");
    while (Clock::now() < deadline && lit == 7)
      lit = json_number(client->ask("state"), "candles_lit");
    EXPECT_LT(lit, 7) << "a 30 m/s blowout put no candle out";
  }
  kill(pid, SIGTERM);
  int status = 0;
  waitpid(pid, &status, 0);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << status;
  fs::remove_all(dir);
}

}  // namespace
}  // namespace candela
