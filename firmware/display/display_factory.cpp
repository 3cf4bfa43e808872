// Picks the place to draw. "auto" tries the kiosk first, then a desktop
// window, then headless, and says why it skipped each one.
#include "core/error.h"
#include "core/log.h"
#include "display/display.h"

namespace candela {

std::unique_ptr<Display> open_display(const DisplayOptions& options) {
  using Opener = std::unique_ptr<Display> (*)(const DisplayOptions&);
  struct Backend {
    const char* name;
    Opener open;
  };
  static const Backend kBackends[] = {{"drm", open_drm_display},
                                      {"window", open_window_display},
                                      {"headless", open_headless_display}};
  if (options.kind != "auto") {
    for (const auto& b : kBackends)
      if (options.kind == b.name) return b.open(options);
    throw RuntimeError("--display: expected auto, drm, window or headless, got '" + options.kind +
                       "'");
  }
  std::string reasons;
  for (const auto& b : kBackends) {
    try {
      auto d = b.open(options);
      LOG_INFO("display: using %s", b.name);
      return d;
    } catch (const std::exception& e) {
      LOG_INFO("display: skipping %s: %s", b.name, e.what());
      reasons += std::string("\n  ") + e.what();
    }
  }
  throw RuntimeError("no display could be opened:" + reasons);
}

}  // namespace candela
