#include "display/drm_mode.h"

#include "core/log.h"

namespace candela {

const drmModeModeInfo& choose_mode(const drmModeModeInfo* modes, int count, const DisplayOptions& o,
                                   const std::string& name) {
  const drmModeModeInfo* preferred = &modes[0];
  for (int i = 0; i < count; ++i)
    if (modes[i].type & DRM_MODE_TYPE_PREFERRED) {
      preferred = &modes[i];
      break;
    }
  if (o.width <= 0 && o.refresh_hz <= 0) return *preferred;
  const int want_w = o.width > 0 ? o.width : preferred->hdisplay;
  const int want_h = o.height > 0 ? o.height : preferred->vdisplay;
  const drmModeModeInfo* best = nullptr;
  for (int i = 0; i < count; ++i) {
    const drmModeModeInfo& m = modes[i];
    if (m.hdisplay != want_w || m.vdisplay != want_h) continue;
    if (o.refresh_hz > 0 && static_cast<int>(m.vrefresh) != o.refresh_hz) continue;
    if (m.flags & DRM_MODE_FLAG_INTERLACE) continue;
    // Among equals the preferred one, else the highest refresh.
    if (!best || (m.type & DRM_MODE_TYPE_PREFERRED) ||
        (!(best->type & DRM_MODE_TYPE_PREFERRED) && m.vrefresh > best->vrefresh))
      best = &m;
  }
  if (best) return *best;
  // Appended, not "@" + string: GCC 12's -Wrestrict misfires on that at -O3.
  std::string rate;
  if (o.refresh_hz > 0) rate.append("@").append(std::to_string(o.refresh_hz));
  LOG_WARN("drm: %s has no mode %dx%d%s; using its preferred mode %s", name.c_str(), want_w, want_h,
           rate.c_str(), describe_mode(*preferred).c_str());
  return *preferred;
}

bool needs_new_mode(bool had_screen, uint32_t old_connector, const drmModeModeInfo& old_mode,
                    uint32_t connector, const drmModeModeInfo& mode) {
  // The timings, not the flags of the connector's list (another monitor may
  // list the same mode without marking it preferred) nor the name.
  const drmModeModeInfo& a = old_mode;
  const drmModeModeInfo& b = mode;
  const bool same =
      a.clock == b.clock && a.hdisplay == b.hdisplay && a.hsync_start == b.hsync_start &&
      a.hsync_end == b.hsync_end && a.htotal == b.htotal && a.hskew == b.hskew &&
      a.vdisplay == b.vdisplay && a.vsync_start == b.vsync_start && a.vsync_end == b.vsync_end &&
      a.vtotal == b.vtotal && a.vscan == b.vscan && a.vrefresh == b.vrefresh && a.flags == b.flags;
  return !had_screen || connector != old_connector || !same;
}

std::string describe_mode(const drmModeModeInfo& m) {
  return std::to_string(m.hdisplay) + "x" + std::to_string(m.vdisplay) + "@" +
         std::to_string(m.vrefresh) + ((m.type & DRM_MODE_TYPE_PREFERRED) ? " (preferred)" : "");
}

}  // namespace candela
