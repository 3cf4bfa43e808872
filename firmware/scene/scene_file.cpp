#include "scene/scene_file.h"

#include <cmath>
#include <sstream>

#include "core/error.h"
#include "core/file_read.h"
#include "embedded_scenes.h"
#include "params/params.h"
#include "scene/input_table.h"

namespace candela {
SceneDesc load_scene_text(std::string_view text, const std::string& name,
                          std::span<const ElementKind> more_kinds) {
  const toml::table root = parse_toml_text(text, name);
  SceneDesc scene;
  scene.file = name;
  ParamReader top(&root, name, "");
  scene.seed = static_cast<uint64_t>(top.integer("seed", 1, 0, INT64_MAX));

  ParamReader display = top.table("display");
  scene.width = static_cast<int>(display.integer("width", 0, 0, 16384));
  scene.height = static_cast<int>(display.integer("height", 0, 0, 16384));
  if (display.has("width") != display.has("height"))
    display.fail(display.has("width") ? "height" : "width",
                 "missing: give both width and height, or neither (the display's own size)");
  if (display.has("width") && (scene.width || scene.height))  // 0 x 0: the display's own
    for (const auto& [k, v] : {std::pair{"width", scene.width}, std::pair{"height", scene.height}})
      if (v < 16)
        display.fail(k, "expected at least 16 pixels (as --size), got " + std::to_string(v));
  scene.refresh_hz = static_cast<int>(display.integer("refresh", 0, 0, 1000));
  scene.steps_per_second = static_cast<int>(display.integer("steps_per_second", 60, 10, 1000));
  scene.render_scale = static_cast<float>(display.number("render_scale", 1.0, 0.25, 1.0));
  scene.render_max_height = static_cast<int>(display.integer("render_max_height", 0, 0, 16384));
  if (scene.render_max_height > 0 && scene.render_max_height < 120)
    display.fail("render_max_height", "expected 0 (no limit) or at least 120 rows, got " +
                                          std::to_string(scene.render_max_height));
  display.finish();

  ParamReader bg = top.table("background");
  scene.background = bg.color("color", scene.background);
  bg.finish();

  ParamReader cam = top.table("camera");
  scene.camera.position = cam.vec3("position", scene.camera.position);
  scene.camera.target = cam.vec3("target", scene.camera.target);
  scene.camera.fov_deg = static_cast<float>(cam.number("fov", scene.camera.fov_deg, 5, 150));
  {
    // look_at needs a direction to look in, and one not along "up" (0, 1, 0):
    // otherwise the view is undefined and only the background is drawn.
    const Vec3 d = scene.camera.target - scene.camera.position;
    const double len = std::sqrt(static_cast<double>(d.x) * d.x + static_cast<double>(d.y) * d.y +
                                 static_cast<double>(d.z) * d.z);
    if (!(len > 1e-4))
      cam.fail("target",
               "expected a point away from camera.position (the camera must look at "
               "something), got the same point");
    if (std::fabs(d.y / len) > 0.9999)
      cam.fail("target", std::string("expected the camera to look less than 89 degrees ") +
                             (d.y < 0 ? "down" : "up") +
                             " (straight along the vertical its view is undefined)");
  }
  cam.finish();

  ParamReader wind = top.table("wind");
  scene.wind = parse_wind(wind);

  const bool has_sound = top.has("sound");
  ParamReader sound = top.table("sound");
  scene.sound = parse_sound(sound, has_sound);

  const toml::node* elems = root.get("element");
  top.consume("element");
  if (elems) {
    const toml::array* arr = elems->as_array();
    if (!arr || !arr->is_array_of_tables())
      throw ConfigError(name, "element", "expected an array of tables ([[element]])");
    if (arr->size() > kMaxElements)
      throw ConfigError(name, "element",
                        "expected at most " + std::to_string(kMaxElements) +
                            " [[element]] tables, got " + std::to_string(arr->size()));
    unsigned cost = 0;
    for (size_t i = 0; i < arr->size(); ++i) {
      const toml::table* t = arr->get(i)->as_table();
      const std::string prefix = "element[" + std::to_string(i) + "]";
      ParamReader r(t, name, prefix);
      std::string known;
      const ElementKind* found = nullptr;
      const std::string kind = r.has("kind") ? r.string("kind", "") : "";
      for (const auto kinds : {element_kinds(), more_kinds})
        for (const auto& k : kinds) {
          known += (known.empty() ? "" : ", ") + std::string(k.name);
          if (k.name == kind) found = &k;
        }
      if (!r.has("kind")) r.fail("kind", "missing; expected one of " + known);
      if (!found) r.fail("kind", "expected one of " + known + ", got \"" + echo_value(kind) + "\"");
      SceneDesc::Entry e;
      e.kind = kind;
      e.name = r.string("name", kind + " " + std::to_string(i));
      const Vec3 pos = r.vec3("position", {});
      const auto seed = static_cast<uint64_t>(r.integer("seed", 0, 0, INT64_MAX));
      e.spec = found->parse(r);
      e.spec->position = pos;
      e.spec->seed = seed;
      cost += e.spec->cost();
      if (cost > kMaxElementCost)
        throw ConfigError(name, prefix,
                          "the scene's elements would cost more than the budget of " +
                              std::to_string(kMaxElementCost) + " units (" + kind + " costs " +
                              std::to_string(e.spec->cost()) +
                              "; e.g. at most 16 eigen-flames or 64 candle groups)");
      scene.elements.push_back(std::move(e));
    }
  }
  scene.inputs = parse_inputs(root.get("input"), name);
  top.consume("input");
  top.finish();
  return scene;
}

SceneDesc load_scene_file(const std::string& path) {
  return load_scene_text(read_bounded_file(path, FileKind::kScene), path);
}

std::vector<std::string> scene_problems(const SceneDesc& scene) {
  std::vector<std::string> out;
  if (scene.elements.empty())
    out.push_back(scene.file +
                  ": element: the scene has no [[element]]; the display would stay black");
  for (const auto& e : scene.elements) {
    const std::string p = e.spec->problem();
    if (!p.empty()) out.push_back(scene.file + ": " + p);
  }
  return out;
}

SceneDesc load_builtin_scene(const std::string& name) {
  const auto text = scenes::find(name + ".toml");
  if (text.empty()) throw ConfigError("<built-in " + name + ">", "", "no such built-in scene");
  return load_scene_text(text, "<built-in " + name + ">");
}

}  // namespace candela
