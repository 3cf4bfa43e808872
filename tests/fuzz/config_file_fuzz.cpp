// libFuzzer target for the kiosk config (/etc/candela/candela.toml, issue
// 34): any text must be refused with a ConfigError or load, never crash,
// hang or overflow. A loaded [schedule] is evaluated at every hour of the
// week, at minute 0 and 59, and described as the `schedule` command does:
// its levels stay in [0, 1], a scene index within its scenes, the next
// change within a week; [mqtt] and [room] are read as the kiosk reads them.
//   build with clang: ninja -C build-fuzz config_file_fuzz (tests/fuzz/run-fuzz.sh)
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "app/config_file.h"
#include "app/kiosk.h"
#include "core/error.h"

namespace candela {
// The built-in scenes as the kiosk names them (app/kiosk.cpp without the
// embedded files).
std::vector<std::string> builtin_scene_names() { return {"default", "eigen-fireplace"}; }
std::string builtin_scene_list() { return "default, eigen-fireplace"; }
bool is_scene_name(const std::string& label) {
  return label.find('/') == std::string::npos && !label.ends_with(".toml");
}
}  // namespace candela

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace candela;
  KioskConfig c;
  try {
    c = load_config_text(std::string_view(reinterpret_cast<const char*>(data), size),
                         "/tmp/candela-fuzz/candela.toml");
  } catch (const ConfigError& e) {
    if (std::string_view(e.what()).size() > 4096) __builtin_trap();  // errors stay readable
    return 0;
  }
  const Schedule& s = c.schedule;
  for (int hour = 0; hour < 7 * 24; ++hour)
    for (int minute : {0, 59}) {
      const LocalTime t{hour / 24, (hour % 24) * 3600 + minute * 60};
      const ScheduleNow now = evaluate_schedule(s, t);
      if (!(now.level >= 0 && now.level <= 1) || !(now.volume >= 0 && now.volume <= 1))
        __builtin_trap();
      if (now.scene < -1 || now.scene >= static_cast<int>(s.scenes.size())) __builtin_trap();
      if (now.has_next && (now.next_in_s <= 0 || now.next_in_s > 7 * 86400)) __builtin_trap();
      if (minute == 0 && hour % 6 == 0 && describe_schedule(s, t, "default").empty())
        __builtin_trap();
    }
  return 0;
}
