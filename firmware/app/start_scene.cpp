#include "app/start_scene.h"

#include <cstdio>

#include "app/kiosk.h"
#include "app/schedule.h"
#include "core/error.h"

namespace candela {

StartScene choose_start_scene(const Options& opt, const WallClock& wall) {
  StartScene start;
  start.config_label = opt.test_pattern           ? "test-pattern"
                       : opt.scene.empty()        ? "default"
                       : opt.scene_is_name        ? opt.scene
                       : is_scene_name(opt.scene) ? "./" + opt.scene  // --scene FILE
                                                  : opt.scene;
  start.label = start.config_label;
  if (opt.schedule.present && !opt.test_pattern && !opt.check) {
    const ScheduleNow now = evaluate_schedule(opt.schedule, local_time(wall.now_ms() / 1000));
    start.label = scheduled_scene(opt.schedule, now, start.label);
  }
  start.desc = opt.test_pattern                                ? load_builtin_scene("test-pattern")
               : opt.scene.empty() && start.label == "default" ? load_builtin_scene("default")
               : start.label == start.config_label && !opt.scene.empty() && !opt.scene_is_name
                   ? load_scene_file(opt.scene)
                   : load_scene_by_label(start.label);
  return start;
}

int check_start_scene(const Options& opt, const StartScene& start) {
  const std::vector<std::string> problems = scene_problems(start.desc);
  for (const auto& p : problems) std::fprintf(stderr, "candela: error: %s\n", p.c_str());
  // The [schedule]'s scenes too: a kiosk would find a broken one in the evening.
  bool schedule_ok = true;
  for (const auto& range : opt.schedule.scenes) {
    try {
      for (const auto& p : scene_problems(load_scene_by_label(range.scene))) {
        std::fprintf(stderr, "candela: error: %s: schedule.scenes.\"%s\": %s\n", opt.config.c_str(),
                     range.range.c_str(), p.c_str());
        schedule_ok = false;
      }
    } catch (const ConfigError& e) {
      std::fprintf(stderr, "candela: error: %s: schedule.scenes.\"%s\": %s\n", opt.config.c_str(),
                   range.range.c_str(), e.what());
      schedule_ok = false;
    }
  }
  if (!problems.empty() || !schedule_ok) return 2;
  std::printf("%s: OK (%zu elements)\n", start.desc.file.c_str(), start.desc.elements.size());
  return 0;
}

}  // namespace candela
