// Sanitizer builds only: keep the GL driver modules loaded until exit, so
// LeakSanitizer can name them in leak reports (and tests/lsan.supp can
// suppress leaks that belong to Mesa, not to us). Without this, Mesa unloads
// its driver at eglTerminate and its leaks show up as "<unknown module>".
#include <dlfcn.h>

#include <string>

namespace candela {

void pin_gl_drivers() {
  const std::string dri = std::string("/usr/lib/") + CANDELA_MULTIARCH + "/dri/";
  for (const char* lib :
       {"libEGL_mesa.so.0", "libglapi.so.0", "swrast_dri.so", "kms_swrast_dri.so"}) {
    // RTLD_NOLOAD: pin only what the EGL driver has already loaded.
    if (!dlopen(lib, RTLD_LAZY | RTLD_NOLOAD | RTLD_NODELETE))
      dlopen((dri + lib).c_str(), RTLD_LAZY | RTLD_NOLOAD | RTLD_NODELETE);
  }
}

}  // namespace candela
