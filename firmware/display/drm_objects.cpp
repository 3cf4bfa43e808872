#include "display/drm_objects.h"

#include <cstring>

namespace candela::drm {

std::string connector_name(const drmModeConnector& c) {
  const char* type = drmModeGetConnectorTypeName(c.connector_type);
  return std::string(type ? type : "Unknown") + "-" + std::to_string(c.connector_type_id);
}

const char* connection_name(drmModeConnection c) {
  switch (c) {
    case DRM_MODE_CONNECTED:
      return "connected";
    case DRM_MODE_DISCONNECTED:
      return "disconnected";
    default:
      return "unknown";
  }
}

// The CRTC to drive the connector with: the one already driving it if any,
// else the first one an encoder of the connector can use.
int pick_crtc(int fd, const drmModeRes& res, const drmModeConnector& conn, uint32_t& crtc_id) {
  if (conn.encoder_id) {
    Encoder enc(drmModeGetEncoder(fd, conn.encoder_id));
    if (enc && enc->crtc_id)
      for (int i = 0; i < res.count_crtcs; ++i)
        if (res.crtcs[i] == enc->crtc_id) {
          crtc_id = enc->crtc_id;
          return i;
        }
  }
  for (int e = 0; e < conn.count_encoders; ++e) {
    Encoder enc(drmModeGetEncoder(fd, conn.encoders[e]));
    if (!enc) continue;
    for (int i = 0; i < res.count_crtcs; ++i)
      if (enc->possible_crtcs & (1u << i)) {
        crtc_id = res.crtcs[i];
        return i;
      }
  }
  return -1;
}

// The modifiers the plane's IN_FORMATS blob lists for `format`.
std::vector<uint64_t> plane_modifiers(int fd, uint32_t plane_id, uint32_t format) {
  std::vector<uint64_t> mods;
  PropertyTable props(fd, plane_id, DRM_MODE_OBJECT_PLANE);
  uint64_t blob_id = 0;
  if (!props.value("IN_FORMATS", blob_id) || blob_id == 0) return mods;
  Blob blob(drmModeGetPropertyBlob(fd, static_cast<uint32_t>(blob_id)));
  if (!blob) return mods;
  drmModeFormatModifierIterator it{};
  while (drmModeFormatModifierBlobIterNext(blob.get(), &it))
    if (it.fmt == format) mods.push_back(it.mod);
  return mods;
}

}  // namespace candela::drm
