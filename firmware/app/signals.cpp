#include "app/signals.h"

#include <signal.h>

#include <csignal>

#include "app/kiosk.h"

namespace candela {
namespace {
std::atomic<bool> g_stop{false};
volatile std::sig_atomic_t g_signal = 0;
Kiosk* volatile g_kiosk = nullptr;  // set while SIGHUP means "reload"

void on_signal(int sig) {
  g_signal = sig;
  g_stop = true;
}
void on_reload_signal(int) {
  if (Kiosk* k = g_kiosk) k->request_reload();
}
}  // namespace

void install_stop_signals() {
  struct sigaction sa {};
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESETHAND;
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) sigaction(sig, &sa, nullptr);
  std::signal(SIGPIPE, SIG_IGN);
}

const std::atomic<bool>& stop_requested() { return g_stop; }

const char* stop_signal_name() {
  const int sig = g_signal;
  return sig == SIGTERM  ? "SIGTERM"
         : sig == SIGINT ? "SIGINT"
         : sig == SIGHUP ? "SIGHUP"
                         : "a signal";
}

void reload_on_sighup(Kiosk* kiosk) {
  const bool install = kiosk && !g_kiosk;
  g_kiosk = kiosk;
  if (!install) return;
  struct sigaction sa {};
  sa.sa_handler = on_reload_signal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESTART;
  sigaction(SIGHUP, &sa, nullptr);
}

}  // namespace candela
