// Scene files (TOML): display settings, background, camera, wind and a list
// of [[element]] tables. Loading validates everything, so `candela --check`
// and start-up report the same errors.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "gl/math.h"
#include "input/input_spec.h"
#include "scene/element.h"
#include "wind/wind_field.h"

namespace candela {

struct CameraDesc {
  Vec3 position{0.0f, 0.25f, 2.4f};
  Vec3 target{0.0f, 0.2f, 0.0f};
  float fov_deg = 35.0f;
};

struct SceneDesc {
  std::string file;  // path, or "<built-in NAME>"
  int width = 0, height = 0, refresh_hz = 0;
  int steps_per_second = 60;
  uint64_t seed = 1;
  Vec3 background{0.02f, 0.015f, 0.012f};
  CameraDesc camera;
  WindSpec wind;
  struct Entry {
    std::string kind;
    std::string name;
    std::unique_ptr<ElementSpec> spec;
  };
  std::vector<Entry> elements;
  std::vector<InputSpec> inputs;  // [[input]]: GPIO sensors, camera (firmware/input)
};

// Throws ConfigError (file, key, what was expected).
SceneDesc load_scene_file(const std::string& path);
SceneDesc load_scene_text(std::string_view text, const std::string& name);
// Built-in scenes ("default", "test-pattern", ...): firmware/scenes/*.toml.
SceneDesc load_builtin_scene(const std::string& name);

}  // namespace candela
