// candela-state-hash: runs built-in scenes for N fixed animation steps,
// without drawing, and prints a 64-bit hash of their animation state
// (Scene::hash_state after every step, folded together), with the running
// hash every --every steps so a difference shows where it began; it saves
// the frame drawn at the --frames-at steps as PNGs. Built for amd64 and for
// arm64 (board/arm64/cross-build.sh): tests/arm64/compare_builds.py runs
// both and requires identical hashes and frames within 2 LSB.
//   candela-state-hash [--steps N] [--every K] [--size WxH] [--frames-at A,B] [--out DIR] SCENE...
// Output lines: "SCENE step=K hash=HEX" and "SCENE steps=N hash=HEX elements=E".
#include <CLI/CLI.hpp>
#include <cinttypes>
#include <cstdio>
#include <string>
#include <vector>

#include "core/clock.h"
#include "core/state_hash.h"
#include "core/wxh.h"
#include "scene/scene_file.h"
#include "support/render_harness.h"

namespace {

int run(const std::string& name, uint64_t steps, uint64_t every, int width, int height,
        const std::vector<uint64_t>& frames_at, const std::string& out) {
  candela::SceneDesc desc = candela::load_builtin_scene(name);
  const size_t listed = desc.elements.size();
  const int sps = desc.steps_per_second;
  candela::test::RenderHarness harness(std::move(desc), width, height);
  candela::Scene& scene = harness.scene();
  if (scene.failed_elements() != 0 || scene.element_count() != listed) {
    std::fprintf(stderr, "%s: %zu of %zu elements failed to start\n", name.c_str(),
                 scene.failed_elements(), listed);
    return 1;
  }
  candela::StepClock clock(sps);
  candela::StepContext step;
  step.dt = clock.step_seconds();
  candela::StateHash total;
  for (uint64_t i = 1; i <= steps; ++i) {
    step.step = clock.steps();
    step.time = clock.seconds();
    scene.update(step);
    clock.tick();
    candela::StateHash h;
    scene.hash_state(h);
    total.add(h.value());
    if (every > 0 && i % every == 0)
      std::printf("%s step=%" PRIu64 " hash=%016" PRIx64 "\n", name.c_str(), i, total.value());
    for (uint64_t f : frames_at)
      if (f == i && !out.empty())
        harness.read().save_png(out + "/" + name + "-" + std::to_string(i) + ".png");
  }
  std::printf("%s steps=%" PRIu64 " hash=%016" PRIx64 " elements=%zu\n", name.c_str(), steps,
              total.value(), listed);
  std::fflush(stdout);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"candela-state-hash: a hash of built-in scenes' animation state"};
  uint64_t steps = 10000, every = 1000;
  std::string size = "160x90", out;
  std::vector<uint64_t> frames_at;
  std::vector<std::string> scenes;
  app.add_option("--steps", steps, "Animation steps per scene")->check(CLI::Range(1, 10000000));
  app.add_option("--every", every, "Print the running hash every K steps (0: only at the end)");
  app.add_option("--size", size, "Frame size WxH");
  app.add_option("--frames-at", frames_at, "Save the frame after these steps (needs --out)")
      ->delimiter(',');
  app.add_option("--out", out, "Folder for the PNG frames");
  app.add_option("scenes", scenes, "Built-in scene names (firmware/scenes/NAME.toml)")->required();
  CLI11_PARSE(app, argc, argv);
  const auto wxh = candela::parse_wxh(size, {16, 16}, {4096, 4096});
  if (!wxh) {
    std::fprintf(stderr, "--size: expected WxH (16..4096 each), got %s\n", size.c_str());
    return 2;
  }
  const int w = wxh->width, h = wxh->height;
  int status = 0;
  for (const auto& name : scenes) {
    try {
      status |= run(name, steps, every, w, h, frames_at, out);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "%s: %s\n", name.c_str(), e.what());
      status = 1;
    }
  }
  return status;
}
