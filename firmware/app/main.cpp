// candela: the runtime. A thin main over the candela_runtime library.
#include <csignal>
#include <cstdio>

#include "app/frame_loop.h"
#include "app/options.h"
#include "core/error.h"
#include "core/log.h"
#include "display/display.h"
#include "input/input_hub.h"
#include "scene/scene.h"
#include "scene/scene_file.h"

namespace {
std::atomic<bool> g_stop{false};
void on_signal(int) { g_stop = true; }
}  // namespace

int main(int argc, char** argv) {
  using namespace candela;
  Options opt;
  if (int rc = parse_options(argc, argv, opt); rc >= 0) return rc;
  static const char* const kLevels[] = {"debug", "info", "warn", "error"};
  for (int i = 0; i < 4; ++i)
    if (opt.log_level == kLevels[i]) set_log_level(static_cast<LogLevel>(i));

  if (opt.list_elements) {
    for (const auto& k : element_kinds())
      std::printf("%-14.*s %.*s\n", static_cast<int>(k.name.size()), k.name.data(),
                  static_cast<int>(k.summary.size()), k.summary.data());
    return 0;
  }

  SceneDesc desc;
  try {
    desc = opt.test_pattern    ? load_builtin_scene("test-pattern")
           : opt.scene.empty() ? load_builtin_scene("default")
                               : load_scene_file(opt.scene);
  } catch (const ConfigError& e) {
    std::fprintf(stderr, "candela: %s\n", e.what());
    return 2;
  }
  if (opt.check) {
    std::printf("%s: OK (%zu elements)\n", desc.file.c_str(), desc.elements.size());
    return 0;
  }
  if (opt.display.width == 0 && desc.width > 0) {
    opt.display.width = desc.width;
    opt.display.height = desc.height;
  }
  if (opt.display.refresh_hz == 0) opt.display.refresh_hz = desc.refresh_hz;

  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  try {
    auto display = open_display(opt.display);
    Scene scene(desc, opt.seed);
    FrameStats stats(opt.frames ? opt.frames : (1u << 16));
    LoopSettings ls;
    ls.max_frames = opt.frames;
    ls.steps_per_second = desc.steps_per_second;
    ls.frames_per_second = opt.display.fps;
    ls.stop = &g_stop;
    ls.realtime = opt.realtime;
    ls.stats = &stats;
    InputHub inputs(desc.inputs, desc.wind, opt.control);
    inputs.start();
    ls.inputs = &inputs;
    const double cpu0 = process_cpu_seconds();
    const LoopResult r = run_frame_loop(*display, scene, ls);
    const double cpu = process_cpu_seconds() - cpu0;
    display->finish();
    LOG_INFO("%llu frames, %llu steps", static_cast<unsigned long long>(r.frames),
             static_cast<unsigned long long>(r.steps));
    if (opt.bench)
      std::printf("%s\n",
                  stats
                      .json(r.frames, cpu, display->missed_vblanks(), std::string(display->name()),
                            display->width(), display->height(), desc.file)
                      .c_str());
  } catch (const std::exception& e) {
    LOG_ERROR("%s", e.what());
    return 1;
  }
  return 0;
}
