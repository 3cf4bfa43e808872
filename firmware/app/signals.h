// How signals reach candela. SIGTERM (systemd), SIGINT (Ctrl-C) and SIGHUP
// (a closed terminal) end the run cleanly: the frame loop stops, every
// output is finished (an mp4 gets its index, no PNG .tmp or partial y4m
// frame is left) and candela exits 0. A second one of them kills at once
// (SA_RESETHAND), for a stuck shutdown. SIGPIPE is ignored: a write to a gone
// reader (ffmpeg, a control client) returns EPIPE and is reported, instead of
// killing the display silently. A kiosk with --config reloads on SIGHUP.
#pragma once

#include <atomic>

namespace candela {

class Kiosk;

void install_stop_signals();
// Set once a stop signal came (the frame loop and scene building watch it).
const std::atomic<bool>& stop_requested();
const char* stop_signal_name();  // "SIGTERM", ...
// From now on SIGHUP asks `kiosk` to re-read its config (async-signal-safe:
// an eventfd write); null: the kiosk is gone, SIGHUP does nothing.
void reload_on_sighup(Kiosk* kiosk);

}  // namespace candela
