// candela's run, once the command line is parsed and the start-up scene
// chosen (app/main.cpp hands over here): the display, the sound, the scene
// (the built-in default where none of its elements can be made), the kiosk
// (config reloads, schedule, screen power), the inputs and MQTT, then the
// frame loop; afterwards every output finished and the run reported
// (--bench: its JSON line). Returns the exit status.
#pragma once

#include "app/options.h"
#include "app/start_scene.h"
#include "core/clock.h"

namespace candela {

int run_candela(Options& opt, StartScene start, const WallClock& wall);

}  // namespace candela
