// Scene files (TOML): display settings, background, camera, wind and a list
// of [[element]] tables. Loading validates everything, so `candela --check`
// and start-up report the same errors.
#pragma once

#include <toml++/toml.h>

#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "gl/math.h"
#include "params/toml_text.h"
#include "scene/element.h"
#include "scene/input_spec.h"
#include "sound/sound_settings.h"
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
  // [display] render_scale, render_max_height: the scene drawn at a reduced
  // size and scaled up to the screen (scene/scaled_render.h); 1 and 0: the
  // screen's size.
  float render_scale = 1.0f;
  int render_max_height = 0;
  uint64_t seed = 1;
  Vec3 background{0.02f, 0.015f, 0.012f};
  CameraDesc camera;
  WindSpec wind;
  SoundSettings sound;  // [sound]: off unless the scene has the table
  struct Entry {
    std::string kind;
    std::string name;
    std::unique_ptr<ElementSpec> spec;
  };
  std::vector<Entry> elements;
  std::vector<InputSpec> inputs;  // [[input]]: GPIO sensors, camera (firmware/input)
};

// Bounds on what a scene may ask for (README: "Limits"; the nesting bound is in
// params/toml_text.h). More elements would exhaust memory.
inline constexpr size_t kMaxElements = 64;
inline constexpr unsigned kMaxElementCost = 64;  // sum of ElementSpec::cost()

// Throws ConfigError (file, key, what was expected). The file must be a
// regular file within the scene size limit (core/file_read.h).
SceneDesc load_scene_file(const std::string& path);
// `more_kinds`: element kinds besides element_kinds() (a test's own).
SceneDesc load_scene_text(std::string_view text, const std::string& name,
                          std::span<const ElementKind> more_kinds = {});
// Built-in scenes ("default", "test-pattern", ...): firmware/scenes/*.toml.
SceneDesc load_builtin_scene(const std::string& name);

// What makes a loaded scene useless though it parses: no elements (a black
// screen), or an element that would fall back (ElementSpec::problem()).
// Each entry reads "file: key: why". `candela --check` fails on any.
std::vector<std::string> scene_problems(const SceneDesc& scene);

}  // namespace candela
