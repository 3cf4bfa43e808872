// candela: the runtime. A thin main over the candela_runtime library: it
// parses the command line, picks the start-up scene and hands over.
#include <cstdio>
#include <memory>
#include <string>

#include "app/heap_tuning.h"
#include "app/options.h"
#include "app/run_candela.h"
#include "app/signals.h"
#include "app/start_scene.h"
#include "core/clock.h"
#include "core/error.h"
#include "core/log.h"
#include "scene/element.h"
#include "scene/scene_file.h"

int main(int argc, char** argv) {
  using namespace candela;
  keep_freed_heap_memory();
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
  install_stop_signals();
  // The kiosk's clock (the [schedule]'s): the system's, or a test's.
  SystemWallClock system_clock;
  std::unique_ptr<ScaledWallClock> test_clock;
  if (opt.clock_start_ms >= 0)
    test_clock = std::make_unique<ScaledWallClock>(opt.clock_start_ms, opt.clock_scale);
  const WallClock& wall = test_clock ? static_cast<const WallClock&>(*test_clock) : system_clock;
  StartScene start;
  try {
    start = choose_start_scene(opt, wall);
  } catch (const ConfigError& e) {
    std::fprintf(stderr, "candela: %s\n", e.what());
    return 2;
  }
  if (opt.check) return check_start_scene(opt, start);
  // Run anyway (an input-only scene is how sensors are tried out), but say so.
  if (start.desc.elements.empty()) LOG_WARN("%s", scene_problems(start.desc).front().c_str());
  return run_candela(opt, std::move(start), wall);
}
