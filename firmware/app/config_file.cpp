#include "app/config_file.h"

#include <algorithm>

#include "app/kiosk.h"
#include "core/file_read.h"
#include "params/params.h"
#include "scene/scene_file.h"

namespace candela {

KioskConfig load_config_file(const std::string& path) {
  return load_config_text(read_bounded_file(path, FileKind::kScene), path);
}

KioskConfig load_config_text(std::string_view text, const std::string& path) {
  const toml::table root = parse_toml_text(text, path);
  ParamReader r(&root, path, "");
  KioskConfig c;
  // path(): resolved against the config's folder, and refused now if it is
  // not a readable regular file (the scene reader then validates its contents).
  // A built-in scene's name ("eigen-fireplace": what the MQTT select offers
  // and `state` reports) or a scene file's path.
  c.scene = r.string("scene", "");
  if (r.has("scene") && c.scene.empty())
    r.fail("scene", "expected a built-in scene's name or a scene file's path, got an empty string");
  if (!c.scene.empty() && is_scene_name(c.scene)) {
    const std::vector<std::string> names = builtin_scene_names();
    if (std::find(names.begin(), names.end(), c.scene) == names.end()) {
      r.fail("scene", "expected a built-in scene (" + builtin_scene_list() +
                          ") or a scene file's path (with a '/' "
                          "or ending in .toml), got \"" +
                          echo_value(c.scene) + "\"");
    }
  } else {
    c.scene = r.path("scene");
  }
  c.display = r.string("display", "", {"auto", "drm", "window", "headless"});
  const bool has_mqtt = r.has("mqtt");
  ParamReader mqtt = r.table("mqtt");
  c.mqtt = parse_mqtt(mqtt, has_mqtt);
  const bool has_room = r.has("room");
  ParamReader room = r.table("room");
  c.mqtt.room = parse_room(room, has_room, has_mqtt);
  const bool has_schedule = r.has("schedule");
  ParamReader schedule = r.table("schedule");
  c.schedule = parse_schedule(schedule, has_schedule, path);
  r.finish();
  return c;
}

}  // namespace candela
