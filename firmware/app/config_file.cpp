#include "app/config_file.h"

#include "core/file_read.h"
#include "scene/params.h"
#include "scene/scene_file.h"

namespace candela {

KioskConfig load_config_file(const std::string& path) {
  const toml::table root = parse_toml_text(read_bounded_file(path, FileKind::kScene), path);
  ParamReader r(&root, path, "");
  KioskConfig c;
  // path(): resolved against the config's folder, and refused now if it is
  // not a readable regular file (the scene reader then validates its contents).
  c.scene = r.path("scene");
  if (r.has("scene") && c.scene.empty())
    r.fail("scene", "expected a scene file's path, got an empty string");
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
