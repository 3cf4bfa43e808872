// Renders a scene headless, frame by frame, and reads back pixels, for
// tests that check what a viewer would see.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "app/frame_loop.h"
#include "display/display.h"
#include "scene/scene.h"
#include "scene/scene_file.h"

namespace candela::test {

struct Rgba {
  int r, g, b, a;
};

// A frame read back, rows top to bottom.
struct Frame {
  int width = 0, height = 0;
  std::vector<uint8_t> rgba;
  Rgba at(int x, int y) const {
    const uint8_t* p = &rgba[(static_cast<size_t>(y) * width + x) * 4];
    return {p[0], p[1], p[2], p[3]};
  }
  double luma(int x, int y) const {
    const Rgba c = at(x, y);
    return 0.299 * c.r + 0.587 * c.g + 0.114 * c.b;
  }
  void save_png(const std::string& path) const;
  // The pixels whose luma is above `gray` (0..255): how many, and the first
  // and last rows holding one (top = height, bottom = -1 when none).
  struct Lit {
    int count = 0, top = 0, bottom = -1;
  };
  Lit lit_above(double gray) const;
  // The mean luma of the columns x0..x1-1 of the rows y0..y1-1 (top row 0).
  double mean_luma(int x0, int y0, int x1, int y1) const;
  // Separate regions (4-connected) of pixels whose luma is above `gray`, of
  // at least `min_pixels` pixels, in the rows above `rows` (all: -1).
  int regions_above(double gray, int min_pixels = 1, int rows = -1) const;
};

class RenderHarness {
 public:
  // The scene is TOML text (or a SceneDesc); seed 0 = the scene's own.
  // `display` picks the backend ("headless", or "window" under Xvfb).
  RenderHarness(const std::string& scene_toml, int width, int height, uint64_t seed = 0,
                const char* display = "headless");
  RenderHarness(SceneDesc desc, int width, int height, uint64_t seed = 0,
                const char* display = "headless");
  ~RenderHarness();

  // Runs `frames` frames in lockstep (1 step per frame at 60 steps/s).
  void run(uint64_t frames);
  // Hands each frame's time to the scene, as a live display does (automatic
  // quality follows it); off by default, as in any lockstep run.
  void time_frames(bool on) { time_frames_ = on; }
  // Draws the last presented frame again and reads it back before it is
  // presented (so it works on every backend, not only headless). Uses the
  // current GL context: keep one harness alive at a time.
  Frame read();
  uint64_t frames() const { return frames_; }
  Scene& scene() { return *scene_; }
  Display& display() { return *display_; }

 private:
  SceneDesc desc_;
  std::unique_ptr<Display> display_;
  std::unique_ptr<Scene> scene_;
  uint64_t frames_ = 0;
  uint64_t seed_;
  bool time_frames_ = false;
};

}  // namespace candela::test
