// The kiosk: DRM/KMS + GBM + EGL. (First slice: not yet implemented.)
#include "core/error.h"
#include "display/display.h"

namespace candela {

std::unique_ptr<Display> open_drm_display(const DisplayOptions&) {
  throw RuntimeError("drm: not implemented yet");
}

}  // namespace candela
