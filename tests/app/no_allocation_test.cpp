// Once running, the frame loop must not allocate: count operator new calls
// while a scene runs headless after warm-up.
#include <gtest/gtest.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <algorithm>
#include <cstddef>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "app/frame_loop.h"
#include "app/sd_notify.h"
#include "support/allocation_counter.h"
#include "support/render_harness.h"

namespace candela {
namespace {

// The scenes whose frame loop must be allocation-free. Later element kinds
// add their scenes here.
const char* const kScenes[] = {"test-pattern", "default", "eigen-fireplace", "eigen-candle",
                               "eigen-story"};

// Plays systemd for the frame loop: an abstract datagram socket (no file
// left behind) named in NOTIFY_SOCKET, with a 2 us watchdog (a ping every
// frame). Returns the socket to read the notifications from, or -1.
int listen_as_systemd(const std::string& name) {
  const int rx = socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  if (rx < 0) return -1;
  sockaddr_un a{};
  a.sun_family = AF_UNIX;
  std::memcpy(a.sun_path + 1, name.data(), name.size());
  if (bind(rx, reinterpret_cast<sockaddr*>(&a),
           static_cast<socklen_t>(offsetof(sockaddr_un, sun_path) + 1 + name.size())) != 0) {
    close(rx);
    return -1;
  }
  setenv("NOTIFY_SOCKET", ("@" + name).c_str(), 1);
  setenv("WATCHDOG_USEC", "2", 1);
  return rx;
}

TEST(FrameLoop, NoHeapAllocationPerFrame) {
#if defined(__SANITIZE_ADDRESS__)
  // ASan replaces operator new itself, and Mesa's LLVM then frees our blocks
  // through it; the normal build runs this check.
  GTEST_SKIP() << "allocation counting needs the plain allocator";
#endif
  for (const char* name : kScenes) {
    SCOPED_TRACE(name);
    DisplayOptions o;
    o.kind = "headless";
    o.width = 160;
    o.height = 90;
    auto display = open_display(o);
    const SceneDesc desc = load_builtin_scene(name);
    Scene scene(desc);
    LoopSettings s;
    s.max_frames = 10;  // warm-up: first-use allocations in drivers and caches
    run_frame_loop(*display, scene, s);
    s.max_frames = 120;
    LoopResult r;
    EXPECT_EQ(test::allocations_during([&] { r = run_frame_loop(*display, scene, s); }), 0)
        << "operator new called during the frame loop";
    EXPECT_EQ(r.frames, 120u);
  }
}

// The systemd notifications (READY, a WATCHDOG ping every frame, STATUS)
// come from the frame loop too: still no allocation, and a full receiver
// queue (nobody reading) drops messages instead of blocking the loop.
TEST(FrameLoop, NoHeapAllocationWithSystemdNotify) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "allocation counting needs the plain allocator";
#endif
  const int rx = listen_as_systemd("candela-alloc-test-" + std::to_string(getpid()));
  ASSERT_GE(rx, 0);
  DisplayOptions o;
  o.kind = "headless";
  o.width = 160;
  o.height = 90;
  auto display = open_display(o);
  Scene scene(load_builtin_scene("default"));
  LoopSettings s;
  s.max_frames = 10;
  run_frame_loop(*display, scene, s);
  SdNotify notify = SdNotify::from_environment("default.toml");
  ASSERT_TRUE(notify.enabled());
  EXPECT_EQ(getenv("NOTIFY_SOCKET"), nullptr) << "children would inherit NOTIFY_SOCKET";
  s.notify = &notify;
  s.max_frames = 120;
  LoopResult r;
  EXPECT_EQ(test::allocations_during([&] { r = run_frame_loop(*display, scene, s); }), 0)
      << "operator new called during the frame loop";
  EXPECT_EQ(r.frames, 120u);
  char buf[256];
  const ssize_t n = recv(rx, buf, sizeof(buf) - 1, MSG_DONTWAIT);
  ASSERT_GT(n, 0);
  buf[n] = '\0';
  EXPECT_EQ(std::string(buf).rfind("READY=1\nSTATUS=default.toml: frame 1 presented", 0), 0u)
      << buf;
  close(rx);
}

// A display with nowhere to show for a while (DRM with no monitor until
// one is plugged in): the loop draws and presents nothing, tells systemd it
// waits for a screen (READY=1 with that status, then watchdog pings: it is
// healthy), allocates nothing meanwhile, and draws once the screen is there.
class ScreenLaterDisplay final : public Display {
 public:
  ScreenLaterDisplay(std::unique_ptr<Display> inner, int waits)
      : inner_(std::move(inner)), waits_left_(waits) {}
  std::string_view name() const override { return "screen-later"; }
  int width() const override { return inner_->width(); }
  int height() const override { return inner_->height(); }
  bool paced_by_vsync() const override { return false; }
  void begin_frame() override { inner_->begin_frame(); }
  void present() override {
    if (waits_left_ > 0) ++presented_without_screen;
    inner_->present();
  }
  bool poll_events(DisplayEvents& e) override { return inner_->poll_events(e); }
  bool screen_present() const override { return waits_left_ == 0; }
  bool wait_for_screen(int timeout_ms) override {
    EXPECT_GT(timeout_ms, 0) << "the wait must be bounded and not a busy loop";
    if (waits_left_ > 0) --waits_left_;
    ++waits;
    return waits_left_ == 0;
  }
  int waits = 0, presented_without_screen = 0;

 private:
  std::unique_ptr<Display> inner_;
  int waits_left_;
};

TEST(FrameLoop, WaitsForAScreenThenDraws) {
  const int rx = listen_as_systemd("candela-screen-test-" + std::to_string(getpid()));
  ASSERT_GE(rx, 0);
  DisplayOptions o;
  o.kind = "headless";
  o.width = 160;
  o.height = 90;
  ScreenLaterDisplay display(open_display(o), 50);
  Scene scene(load_builtin_scene("default"));
  SdNotify notify = SdNotify::from_environment("default.toml");
  ASSERT_TRUE(notify.enabled());
  LoopSettings s;
  s.notify = &notify;
  s.max_frames = 5;
  const LoopResult r = run_frame_loop(display, scene, s);
  EXPECT_EQ(display.waits, 50) << "the loop waits on the display while there is no screen";
  EXPECT_EQ(display.presented_without_screen, 0) << "frames presented with no screen";
  EXPECT_EQ(r.frames, 5u) << "frames presented once the screen is there";
  std::vector<std::string> got;
  char buf[256];
  for (ssize_t n; (n = recv(rx, buf, sizeof(buf) - 1, MSG_DONTWAIT)) > 0;)
    got.emplace_back(buf, static_cast<size_t>(n));
  close(rx);
  ASSERT_FALSE(got.empty());
  EXPECT_EQ(got.front(), "READY=1\nSTATUS=default.toml: waiting for a screen")
      << "systemd hears first that the kiosk runs and waits";
  EXPECT_EQ(
      std::count(got.begin(), got.end(), "STATUS=default.toml: waiting for a screen") +
          std::count(got.begin(), got.end(), "READY=1\nSTATUS=default.toml: waiting for a screen"),
      1)
      << "said once";
  EXPECT_GE(std::count(got.begin(), got.end(), "WATCHDOG=1"), 2)
      << "watchdog pings go on while waiting";
}

}  // namespace
}  // namespace candela
