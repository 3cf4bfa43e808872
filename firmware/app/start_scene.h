// Which scene candela starts with, decided in one place: --test-pattern, the
// [schedule]'s scene for now, --scene (a file or a built-in's name), the
// --config file's scene, or the built-in default. And `--check`: that scene
// and every scene the schedule names, reported as a kiosk would meet them.
#pragma once

#include <string>

#include "app/options.h"
#include "core/clock.h"
#include "scene/scene_file.h"

namespace candela {

struct StartScene {
  SceneDesc desc;
  std::string label;         // what the kiosk calls it (`state`, `reload`): a name or a path
  std::string config_label;  // the configured scene, which the schedule's ranges fall back to
};

// Throws ConfigError (file, key, what was expected) when the scene cannot be read.
StartScene choose_start_scene(const Options& opt, const WallClock& wall);

// --check: prints the problems of `start` and of every scheduled scene to
// stderr (exit 2), or "FILE: OK (N elements)" (exit 0). What the runtime
// would work around (a model it replaces with the built-in one, an empty
// scene) is still an error in the scene file.
int check_start_scene(const Options& opt, const StartScene& start);

}  // namespace candela
