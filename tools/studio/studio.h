// The studio's frame loop: the runtime's window backend (X11 + EGL), Dear
// ImGui over it (X11Platform + ImGui's OpenGL ES 3 renderer), the session,
// the flame and PCA views, the panels and the scripted input.
#pragma once

#include <string>

namespace candela::studio {

struct StudioOptions {
  std::string model, story;
  int width = 1280, height = 720;
  std::string script;    // --script FILE
  int bench_frames = 0;  // --bench N: N frames unpaced, then one JSON line of frame times
  bool vsync = true;
};

// Returns the exit status: 0, or 2 for a script that failed.
int run_studio(const StudioOptions& options);

}  // namespace candela::studio
