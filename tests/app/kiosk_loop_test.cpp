// The frame loop with live control (app/kiosk.h): a scene handed over by
// another thread is swapped in between two frames, and dimming plus the
// cross-fade allocate nothing per frame.
#include <gtest/gtest.h>

#include <string>
#include <thread>

#include "app/frame_loop.h"
#include "app/kiosk.h"
#include "app/kiosk_post.h"
#include "core/clock.h"
#include "support/allocation_counter.h"

namespace candela {
namespace {

TEST(KioskLoop, SwapsBetweenFramesThenDimsWithoutAllocation) {
  DisplayOptions o;
  o.kind = "headless";
  o.width = 160;
  o.height = 90;
  auto display = open_display(o);
  auto scene = std::make_unique<Scene>(load_builtin_scene("default"));
  FakeWallClock clock(0);
  KioskOptions ko;
  ko.scene_label = "default";
  Kiosk kiosk(std::move(ko), clock);
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
  test::start_counting_allocations();
  const LoopResult r = run_frame_loop(*display, scene, s);
  const long allocations = test::stop_counting_allocations();
  EXPECT_EQ(r.frames, 120u);
  EXPECT_EQ(allocations, 0) << "operator new called during the frame loop";
}

}  // namespace
}  // namespace candela
