#include "support/render_harness.h"

#include <algorithm>
#include <vector>

#include "core/image.h"
#include "gl/gles.h"

namespace candela::test {

Frame::Lit Frame::lit_above(double gray) const {
  Lit lit{0, height, -1};
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      if (luma(x, y) > gray) {
        ++lit.count;
        lit.top = std::min(lit.top, y);
        lit.bottom = std::max(lit.bottom, y);
      }
  return lit;
}

int Frame::regions_above(double gray, int min_pixels, int rows) const {
  const int h = rows < 0 ? height : std::min(rows, height);
  std::vector<char> seen(static_cast<size_t>(width) * height, 0);
  int regions = 0;
  std::vector<int> stack;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < width; ++x) {
      if (seen[y * width + x] || luma(x, y) <= gray) continue;
      int size = 0;
      stack.push_back(y * width + x);
      seen[y * width + x] = 1;
      while (!stack.empty()) {
        const int i = stack.back();
        stack.pop_back();
        ++size;
        const int px = i % width, py = i / width;
        const int nb[4][2] = {{px + 1, py}, {px - 1, py}, {px, py + 1}, {px, py - 1}};
        for (const auto& n : nb) {
          if (n[0] < 0 || n[1] < 0 || n[0] >= width || n[1] >= h) continue;
          const int j = n[1] * width + n[0];
          if (!seen[j] && luma(n[0], n[1]) > gray) {
            seen[j] = 1;
            stack.push_back(j);
          }
        }
      }
      regions += size >= min_pixels;
    }
  return regions;
}

double Frame::mean_luma(int x0, int y0, int x1, int y1) const {
  double sum = 0;
  int n = 0;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      sum += luma(x, y);
      ++n;
    }
  return sum / n;
}

void Frame::save_png(const std::string& path) const {
  write_png(path, width, height, 4, rgba.data());
}

RenderHarness::RenderHarness(const std::string& scene_toml, int width, int height, uint64_t seed,
                             const char* display)
    : RenderHarness(load_scene_text(scene_toml, "<test scene>"), width, height, seed, display) {}

RenderHarness::RenderHarness(SceneDesc desc, int width, int height, uint64_t seed,
                             const char* display)
    : desc_(std::move(desc)), seed_(seed) {
  DisplayOptions o;
  o.kind = display;
  o.vsync = false;
  o.width = width;
  o.height = height;
  display_ = open_display(o);
  scene_ = std::make_unique<Scene>(desc_, seed_);
}

RenderHarness::~RenderHarness() {
  scene_.reset();
  display_.reset();
}

void RenderHarness::run(uint64_t frames) {
  // A fresh loop each call would restart the clock; keep one continuous run
  // by re-running from zero with the total, on a fresh scene.
  frames_ += frames;
  scene_ = std::make_unique<Scene>(desc_, seed_);
  LoopSettings s;
  s.max_frames = frames_;
  s.steps_per_second = desc_.steps_per_second;
  s.frames_per_second = desc_.steps_per_second;
  s.time_lockstep_frames = time_frames_;
  run_frame_loop(*display_, *scene_, s);
}

Frame RenderHarness::read() {
  Frame f;
  f.width = display_->width();
  f.height = display_->height();
  FrameContext ctx;
  ctx.width = f.width;
  ctx.height = f.height;
  ctx.frame = frames_ > 0 ? frames_ - 1 : 0;
  ctx.step = ctx.frame;
  display_->begin_frame();
  scene_->draw(ctx);
  std::vector<uint8_t> up(static_cast<size_t>(f.width) * f.height * 4);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, f.width, f.height, GL_RGBA, GL_UNSIGNED_BYTE, up.data());
  f.rgba.resize(up.size());
  const size_t row = static_cast<size_t>(f.width) * 4;
  for (int y = 0; y < f.height; ++y)
    std::copy_n(&up[row * (f.height - 1 - y)], row, &f.rgba[row * y]);
  return f;
}

}  // namespace candela::test
