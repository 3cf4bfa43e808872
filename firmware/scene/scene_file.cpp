#include "scene/scene_file.h"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

#include "core/error.h"
#include "input/input_config.h"
#include "scene/params.h"

namespace candela::scenes {
std::string_view find(std::string_view name);
}

namespace candela {

SceneDesc load_scene_text(std::string_view text, const std::string& name) {
  toml::table root;
  try {
    root = toml::parse(text, name);
  } catch (const toml::parse_error& e) {
    std::ostringstream where;
    where << "line " << e.source().begin.line << ", column " << e.source().begin.column;
    throw ConfigError(name, where.str(), "TOML syntax error: " + std::string(e.description()));
  }
  SceneDesc scene;
  scene.file = name;
  ParamReader top(&root, name, "");
  scene.seed = static_cast<uint64_t>(top.integer("seed", 1, 0, INT64_MAX));

  ParamReader display = top.table("display");
  scene.width = static_cast<int>(display.integer("width", 0, 0, 16384));
  scene.height = static_cast<int>(display.integer("height", 0, 0, 16384));
  scene.refresh_hz = static_cast<int>(display.integer("refresh", 0, 0, 1000));
  scene.steps_per_second = static_cast<int>(display.integer("steps_per_second", 60, 10, 1000));
  display.finish();

  ParamReader bg = top.table("background");
  scene.background = bg.color("color", scene.background);
  bg.finish();

  ParamReader cam = top.table("camera");
  scene.camera.position = cam.vec3("position", scene.camera.position);
  scene.camera.target = cam.vec3("target", scene.camera.target);
  scene.camera.fov_deg = static_cast<float>(cam.number("fov", scene.camera.fov_deg, 5, 150));
  cam.finish();

  ParamReader wind = top.table("wind");
  scene.wind = parse_wind(wind);

  const toml::node* elems = root.get("element");
  top.consume("element");
  if (elems) {
    const toml::array* arr = elems->as_array();
    if (!arr || !arr->is_array_of_tables())
      throw ConfigError(name, "element", "expected an array of tables ([[element]])");
    for (size_t i = 0; i < arr->size(); ++i) {
      const toml::table* t = arr->get(i)->as_table();
      const std::string prefix = "element[" + std::to_string(i) + "]";
      ParamReader r(t, name, prefix);
      std::string known;
      for (const auto& k : element_kinds())
        known += (known.empty() ? "" : ", ") + std::string(k.name);
      if (!r.has("kind")) r.fail("kind", "missing; expected one of " + known);
      const std::string kind = r.string("kind", "");
      const ElementKind* found = nullptr;
      for (const auto& k : element_kinds())
        if (k.name == kind) found = &k;
      if (!found) r.fail("kind", "expected one of " + known + ", got \"" + kind + "\"");
      SceneDesc::Entry e;
      e.kind = kind;
      e.name = r.string("name", kind + " " + std::to_string(i));
      const Vec3 pos = r.vec3("position", {});
      const auto seed = static_cast<uint64_t>(r.integer("seed", 0, 0, INT64_MAX));
      e.spec = found->parse(r);
      e.spec->position = pos;
      e.spec->seed = seed;
      scene.elements.push_back(std::move(e));
    }
  }
  scene.inputs = parse_inputs(root.get("input"), name);
  top.consume("input");
  top.finish();
  return scene;
}

SceneDesc load_scene_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw ConfigError(path, "", std::string("cannot open scene file: ") + std::strerror(errno));
  std::stringstream ss;
  ss << in.rdbuf();
  return load_scene_text(ss.str(), path);
}

SceneDesc load_builtin_scene(const std::string& name) {
  const auto text = scenes::find(name + ".toml");
  if (text.empty()) throw ConfigError("<built-in " + name + ">", "", "no such built-in scene");
  return load_scene_text(text, "<built-in " + name + ">");
}

}  // namespace candela
