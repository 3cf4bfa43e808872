#include "display/cec_switch.h"

#include <atomic>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "core/log.h"

#if CANDELA_HAVE_LIBCEC
#include <dlfcn.h>
#include <libcec/cec.h>
#endif

namespace candela {
namespace {

std::atomic<bool> g_absence_logged{false};

void log_absent_once(const std::string& why) {
  if (!g_absence_logged.exchange(true))
    LOG_INFO("cec: %s; the screen is switched with DPMS only", why.c_str());
}

#if CANDELA_HAVE_LIBCEC
using InitFn = CEC::ICECAdapter* (*)(CEC::libcec_configuration*);
using DestroyFn = void (*)(CEC::ICECAdapter*);

class CecSwitch final : public ScreenPowerSwitch {
 public:
  CecSwitch(void* lib, CEC::ICECAdapter* cec, DestroyFn destroy, std::string port)
      : lib_(lib), cec_(cec), destroy_(destroy), port_(std::move(port)) {}
  ~CecSwitch() override {
    cec_->Close();
    destroy_(cec_);
    // Never dlclose()d: libcec's threads and static destructors outlive
    // CECDestroy (unloading it crashed at exit now and then).
    (void)lib_;
  }
  std::string name() const override { return "HDMI-CEC on " + port_; }
  bool set_power(bool on) override {
    const bool ok =
        on ? cec_->PowerOnDevices(CEC::CECDEVICE_TV) : cec_->StandbyDevices(CEC::CECDEVICE_TV);
    if (!ok) LOG_WARN("cec: the TV did not take %s", on ? "power on" : "standby");
    return ok;
  }

 private:
  void* lib_;
  CEC::ICECAdapter* cec_;
  DestroyFn destroy_;
  std::string port_;
};

// Where libcec could find an adapter: the kernel's CEC framework
// (/dev/cecN: the Pi's vc4 HDMI, many SoCs) or a Pulse-Eight USB adapter
// (USB vendor 2548). Looked for before loading libcec: no adapter, no
// library in the process (its threads and exit-time destructors with it).
std::string cec_adapter_hint() {
  try {
    std::error_code ec;
    for (const auto& e : std::filesystem::directory_iterator("/dev", ec))
      if (e.path().filename().string().rfind("cec", 0) == 0) return e.path().string();
    for (const auto& e : std::filesystem::directory_iterator("/sys/bus/usb/devices", ec)) {
      std::ifstream f(e.path() / "idVendor");
      std::string vendor;
      if (f >> vendor && vendor == "2548") return "USB " + e.path().filename().string();
    }
  } catch (const std::exception&) {  // a folder that cannot be read: no adapter seen there
  }
  return "";
}
#endif

}  // namespace

std::unique_ptr<ScreenPowerSwitch> open_cec_switch() {
#if CANDELA_HAVE_LIBCEC
  if (cec_adapter_hint().empty()) {
    log_absent_once("no CEC adapter (no /dev/cec*, no Pulse-Eight USB adapter)");
    return nullptr;
  }
  const std::string soname = "libcec.so." CEC_LIB_VERSION_MAJOR_STR;
  void* lib = dlopen(soname.c_str(), RTLD_NOW | RTLD_LOCAL | RTLD_NODELETE);
  if (!lib) {
    log_absent_once(soname + " is not installed (Debian: libcec6)");
    return nullptr;
  }
  auto init = reinterpret_cast<InitFn>(dlsym(lib, "CECInitialise"));
  auto destroy = reinterpret_cast<DestroyFn>(dlsym(lib, "CECDestroy"));
  if (!init || !destroy) {
    log_absent_once(soname + " has no CECInitialise/CECDestroy");
    return nullptr;
  }
  CEC::libcec_configuration config;
  config.Clear();
  config.clientVersion = CEC::LIBCEC_VERSION_CURRENT;
  std::snprintf(config.strDeviceName, sizeof config.strDeviceName, "candela");
  config.deviceTypes.Add(CEC::CEC_DEVICE_TYPE_PLAYBACK_DEVICE);
  config.bActivateSource = 0;
  CEC::ICECAdapter* cec = init(&config);
  if (!cec) {
    log_absent_once("libcec did not initialise");
    return nullptr;
  }
  CEC::cec_adapter_descriptor found[4];
  const int8_t n = cec->DetectAdapters(found, 4, nullptr, true);
  if (n <= 0) {
    destroy(cec);
    log_absent_once("no CEC adapter found");
    return nullptr;
  }
  const std::string port = found[0].strComName;
  if (!cec->Open(port.c_str(), 5000)) {
    destroy(cec);
    log_absent_once("cannot open the CEC adapter " + port);
    return nullptr;
  }
  LOG_INFO("cec: switching the TV through %s too", port.c_str());
  return std::make_unique<CecSwitch>(lib, cec, destroy, port);
#else
  log_absent_once("built without libcec (libcec-dev)");
  return nullptr;
#endif
}

}  // namespace candela
