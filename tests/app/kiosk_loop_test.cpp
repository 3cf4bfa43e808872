// The frame loop with live control (app/kiosk.h): a scene handed over by
// another thread is swapped in between two frames, and dimming plus the
// cross-fade allocate nothing per frame. The control socket's `state` says
// where the frames go: waiting for a screen, then drawing at the size of the
// mode chosen for each monitor plugged in.
#include <gtest/gtest.h>
#include <xf86drmMode.h>

#include <chrono>
#include <cstdio>
#include <functional>
#include <string>
#include <thread>
#include <vector>

#include "app/frame_loop.h"
#include "app/kiosk.h"
#include "app/kiosk_post.h"
#include "core/clock.h"
#include "display/drm_mode.h"
#include "gl/gles.h"
#include "input/input_hub.h"
#include "support/allocation_counter.h"

namespace candela {
namespace {

std::unique_ptr<Display> headless(int width, int height) {
  DisplayOptions o;
  o.kind = "headless";
  o.width = width;
  o.height = height;
  return open_display(o);
}

KioskOptions showing(const char* scene) {
  KioskOptions ko;
  ko.scene_label = scene;
  return ko;
}

TEST(KioskLoop, SwapsBetweenFramesThenDimsWithoutAllocation) {
  auto display = headless(160, 90);
  auto scene = std::make_unique<Scene>(load_builtin_scene("default"));
  FakeWallClock clock(0);
  Kiosk kiosk(showing("default"), clock);
  ControlCommand dim;
  dim.kind = ControlCommand::Kind::kBrightness;
  dim.volume = 0.5f;
  EXPECT_EQ(kiosk.command(dim), "ok");
  KioskPost post;  // made once, as main()'s loop makes it once
  LoopSettings s;
  s.kiosk = &kiosk;
  s.post = &post;
  s.max_frames = 10;  // warm-up
  run_frame_loop(*display, scene, s);
  const Scene* before = scene.get();
  // Another thread asks for a scene; the loop builds it within these frames.
  std::string reply;
  std::thread asker([&] { reply = kiosk.show_scene("test-pattern"); });
  s.max_frames = 0;
  std::atomic<bool> stop{false};
  s.stop = &stop;
  std::thread stopper([&] {
    asker.join();
    stop = true;
  });
  run_frame_loop(*display, scene, s);
  stopper.join();
  EXPECT_EQ(reply, "ok");
  EXPECT_NE(scene.get(), before) << "the loop owns the new scene";
  EXPECT_EQ(kiosk.status().scene, "test-pattern");
  s.stop = nullptr;
  s.max_frames = 5;  // first uses after the swap
  run_frame_loop(*display, scene, s);
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "allocation counting needs the plain allocator";
#endif
  // Dimmed to 0.5: the post pass draws every frame.
  s.max_frames = 120;
  LoopResult r;
  EXPECT_EQ(test::allocations_during([&] { r = run_frame_loop(*display, scene, s); }), 0)
      << "operator new called during the frame loop";
  EXPECT_EQ(r.frames, 120u);
}

// Issue 34: --frames bounds a run although the screen stays off (a schedule
// at night): the frame periods asleep count, so the loop returns after
// about max_frames / fps seconds, having drawn nothing.
TEST(KioskLoop, FramesCountTheScreensOffPeriods) {
  auto display = headless(64, 64);
  auto scene = std::make_unique<Scene>(load_builtin_scene("test-pattern"));
  FakeWallClock clock(0);
  Kiosk kiosk(showing("test-pattern"), clock);
  kiosk.set_screen(false, "test");
  LoopSettings s;
  s.kiosk = &kiosk;
  s.max_frames = 30;  // half a second at 60 fps
  const auto t0 = std::chrono::steady_clock::now();
  const LoopResult r = run_frame_loop(*display, scene, s);
  const double took = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_EQ(r.frames, 0u) << "nothing drawn with the screen off";
  EXPECT_EQ(r.frames_asleep, 30u);
  EXPECT_GE(took, 0.45) << "the periods are real time, not skipped";
}

// A monitor's mode list, as its connector gives it.
drmModeModeInfo mode(int w, int h, bool preferred = false) {
  drmModeModeInfo m{};
  m.hdisplay = static_cast<uint16_t>(w);
  m.vdisplay = static_cast<uint16_t>(h);
  m.htotal = static_cast<uint16_t>(w + 40);
  m.vtotal = static_cast<uint16_t>(h + 10);
  m.vrefresh = 60;
  m.clock = static_cast<uint32_t>(m.htotal * m.vtotal * 60 / 1000);
  m.type = DRM_MODE_TYPE_DRIVER | (preferred ? DRM_MODE_TYPE_PREFERRED : 0);
  std::snprintf(m.name, sizeof m.name, "%dx%d", w, h);
  return m;
}

// The DRM kiosk's screen life through the Display interface: no monitor at
// start, then monitors plugged in and out between frames. Each plug chooses
// the mode as DrmDisplay's hot-plug does (choose_mode from the configured
// size, needs_new_mode), and frames are drawn at that mode's size into a
// headless framebuffer larger than any. `observe` is called before each
// frame and each wait (where a user may ask for `state`).
class ReplugDisplay final : public Display {
 public:
  struct Monitor {
    std::vector<drmModeModeInfo> modes;
    int frames;  // presented before it is unplugged; 0: stays
  };
  struct Shown {
    int width, height;   // the mode's
    int white_bar_end;   // where the test pattern's first (white) bar ends, px from the left
    bool edges_at_mode;  // its right and top border at the mode's edges, nothing beyond
  };
  ReplugDisplay(std::unique_ptr<Display> inner, DisplayOptions wanted,
                std::vector<Monitor> monitors, int waits_before_each, std::function<void()> observe)
      : inner_(std::move(inner)),
        wanted_(wanted),
        monitors_(std::move(monitors)),
        waits_before_each_(waits_before_each),
        waits_left_(waits_before_each),
        observe_(std::move(observe)) {}
  std::string_view name() const override { return "replug"; }
  int width() const override { return mode_.hdisplay; }
  int height() const override { return mode_.vdisplay; }
  bool paced_by_vsync() const override { return false; }
  void begin_frame() override {
    inner_->begin_frame();
    glViewport(0, 0, width(), height());
  }
  void present() override {
    EXPECT_TRUE(screen_) << "presented without a screen";
    // What the frame loop drew: the test pattern's white bar is an eighth of
    // the frame's width, and a one-pixel white border marks its edges.
    const int w = width(), h = height();
    GLint fb = 0;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &fb);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(fb));
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    auto white = [](int x, int y) {
      uint8_t p[4] = {0, 0, 0, 0};
      glReadPixels(x, y, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, p);
      return p[0] > 200 && p[1] > 200 && p[2] > 200;
    };
    auto dark = [](int x, int y) {
      uint8_t p[4] = {255, 255, 255, 255};
      glReadPixels(x, y, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, p);
      return p[0] < 60 && p[1] < 60 && p[2] < 60;
    };
    std::vector<uint8_t> row(static_cast<size_t>(inner_->width()) * 4);
    glReadPixels(0, h - 3, inner_->width(), 1, GL_RGBA, GL_UNSIGNED_BYTE, row.data());
    int bar_end = 0;  // blue is 0 in the second (yellow) bar
    while (bar_end < inner_->width() && row[static_cast<size_t>(bar_end) * 4 + 2] > 200) ++bar_end;
    shown.push_back(
        {w, h, bar_end,
         white(w - 1, h - 3) && dark(w, h - 3) && white(w / 2, h - 1) && dark(w / 2, h)});
    inner_->present();
    if (frames_left_ > 0 && --frames_left_ == 0) {
      screen_ = false;  // unplugged: DrmDisplay's screen_gone()
      waits_left_ = waits_before_each_;
    }
  }
  bool poll_events(DisplayEvents& e) override {
    observe_();
    return inner_->poll_events(e);
  }
  bool screen_present() const override { return screen_; }
  bool wait_for_screen(int timeout_ms) override {
    EXPECT_GT(timeout_ms, 0);
    observe_();
    if (waits_left_ > 0 && --waits_left_ == 0 && next_ < monitors_.size()) {
      // Plugged in: the connector's modes probed, the mode chosen again.
      const Monitor& m = monitors_[next_++];
      const drmModeModeInfo chosen =
          choose_mode(m.modes.data(), static_cast<int>(m.modes.size()), wanted_, "HDMI-A-1");
      if (needs_new_mode(screen_, 1, mode_, 1, chosen)) {
        mode_ = chosen;
        ++setups;
      }
      screen_ = true;
      frames_left_ = m.frames;
    }
    return screen_;
  }
  std::vector<Shown> shown;
  int setups = 0;

 private:
  std::unique_ptr<Display> inner_;
  DisplayOptions wanted_;
  std::vector<Monitor> monitors_;
  size_t next_ = 0;
  int waits_before_each_, waits_left_, frames_left_ = 0;
  bool screen_ = false;
  drmModeModeInfo mode_{};
  std::function<void()> observe_;
};

// The "display" object of a `state` reply.
std::string display_of(const std::string& state) {
  const size_t at = state.find("\"display\":");
  if (at == std::string::npos) return "(no display in " + state + ")";
  return state.substr(at, state.find('}', at) - at + 1);
}

struct ReplugRun {
  std::vector<std::string> seen;  // `state`'s display, each change
  std::string after;              // once the loop is done
  std::vector<ReplugDisplay::Shown> shown;
  int setups = 0;
  uint64_t frames = 0;
};

// A 160x120 monitor (3 frames), unplugged, then a 256x192 one that also lists
// 320x240 and 160x120 (3 frames); `wanted`: the [display] size.
ReplugRun replug_run(DisplayOptions wanted) {
  DisplayOptions o;
  o.kind = "headless";
  o.width = 400;
  o.height = 300;
  FakeWallClock clock(0);
  KioskOptions ko;
  ko.scene_label = "test-pattern";
  Kiosk kiosk(std::move(ko), clock);
  InputHub hub({}, WindSpec{});
  hub.set_kiosk(&kiosk);
  ReplugRun run;
  std::string last;
  auto observe = [&] {
    const std::string d = display_of(hub.answer("state"));
    if (d != last) run.seen.push_back(d);  // each change once
    last = d;
  };
  ReplugDisplay display(open_display(o), wanted,
                        {{{mode(160, 120, true), mode(320, 240)}, 3},
                         {{mode(320, 240), mode(256, 192, true), mode(160, 120)}, 0}},
                        3, observe);
  Scene scene(load_builtin_scene("test-pattern"));
  KioskPost post;
  LoopSettings s;
  s.kiosk = &kiosk;
  s.post = &post;
  s.inputs = &hub;
  s.max_frames = 6;
  run.frames = run_frame_loop(display, scene, s).frames;
  run.after = display_of(hub.answer("state"));
  run.shown = display.shown;
  run.setups = display.setups;
  return run;
}

TEST(KioskLoop, StateSaysWaitingForAScreenThenTheNewMonitorsMode) {
  const ReplugRun r = replug_run(DisplayOptions{});
  EXPECT_EQ(r.frames, 6u);
  ASSERT_EQ(r.seen.size(), 5u);
  EXPECT_EQ(r.seen[0], "\"display\":{\"status\":\"starting\",\"width\":null,\"height\":null}")
      << "before the loop has looked at the display";
  EXPECT_EQ(r.seen[1], "\"display\":{\"status\":\"waiting\",\"width\":null,\"height\":null}")
      << "no monitor yet: waiting, nothing drawn";
  EXPECT_EQ(r.seen[2], "\"display\":{\"status\":\"drawing\",\"width\":160,\"height\":120}")
      << "the first monitor's preferred mode";
  EXPECT_EQ(r.seen[3], "\"display\":{\"status\":\"waiting\",\"width\":160,\"height\":120}")
      << "unplugged: waiting, the size drawn last";
  EXPECT_EQ(r.seen[4], "\"display\":{\"status\":\"drawing\",\"width\":256,\"height\":192}")
      << "the second monitor's preferred mode";
  EXPECT_EQ(r.after, r.seen[4]);
  EXPECT_EQ(r.setups, 2) << "the mode chosen again at the re-plug";
  ASSERT_EQ(r.shown.size(), 6u);
  for (size_t i = 0; i < r.shown.size(); ++i) {
    SCOPED_TRACE(i);
    const ReplugDisplay::Shown& f = r.shown[i];
    EXPECT_EQ(f.width, i < 3 ? 160 : 256);
    EXPECT_EQ(f.height, i < 3 ? 120 : 192);
    EXPECT_NEAR(f.white_bar_end, f.width / 8, 1) << "the frame drawn at the mode's width";
    EXPECT_TRUE(f.edges_at_mode) << "the frame's edges at the mode's width and height";
  }
}

TEST(KioskLoop, ConfiguredSizeWinsAfterAReplugWhereListed) {
  DisplayOptions
      wanted;  // [display] width = 320, height = 240: listed by both, preferred by neither
  wanted.width = 320;
  wanted.height = 240;
  const ReplugRun r = replug_run(wanted);
  ASSERT_EQ(r.shown.size(), 6u);
  for (const ReplugDisplay::Shown& f : r.shown) {
    EXPECT_EQ(f.width, 320);
    EXPECT_EQ(f.height, 240);
    EXPECT_NEAR(f.white_bar_end, 40, 1);
    EXPECT_TRUE(f.edges_at_mode);
  }
  ASSERT_EQ(r.seen.size(), 5u);
  EXPECT_EQ(r.seen[2], "\"display\":{\"status\":\"drawing\",\"width\":320,\"height\":240}");
  EXPECT_EQ(r.seen[4], r.seen[2]);
}

}  // namespace
}  // namespace candela
