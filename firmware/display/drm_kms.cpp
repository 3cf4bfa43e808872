#include "display/drm_kms.h"

#include <dirent.h>
#include <fcntl.h>
#include <unistd.h>
#include <xf86drm.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <optional>
#include <utility>

#include "core/error.h"
#include "core/log.h"
#include "display/drm_mode.h"
#include "display/drm_objects.h"

namespace candela {
namespace {

using namespace drm;

std::string card_list_error(const std::string& tried) {
  return "drm: no display to show on:" + tried;
}

}  // namespace

bool KmsPropertyIds::complete() const {
  return connector_crtc_id && crtc_mode_id && crtc_active && plane_fb_id && plane_crtc_id &&
         plane_src_x && plane_src_y && plane_src_w && plane_src_h && plane_crtc_x && plane_crtc_y &&
         plane_crtc_w && plane_crtc_h;
}

KmsOutput::KmsOutput(KmsOutput&& o) noexcept
    : fd(std::exchange(o.fd, -1)),
      device(std::move(o.device)),
      driver(std::move(o.driver)),
      connector_id(o.connector_id),
      connector_name(std::move(o.connector_name)),
      crtc_id(o.crtc_id),
      plane_id(o.plane_id),
      mode(o.mode),
      atomic(o.atomic),
      addfb2_modifiers(o.addfb2_modifiers),
      modifiers(std::move(o.modifiers)),
      props(o.props) {}

KmsOutput::~KmsOutput() {
  if (fd >= 0) {
    // Leave the display to whoever comes next (a console, another kiosk).
    if (drmIsMaster(fd)) drmDropMaster(fd);
    close(fd);
  }
}

bool probe_kms_connector(KmsOutput& out, const DisplayOptions& options, uint32_t format,
                         std::string& why) {
  const int fd = out.fd;
  // Universal planes before resources, so the primary plane is listed.
  const bool universal = drmSetClientCap(fd, DRM_CLIENT_CAP_UNIVERSAL_PLANES, 1) == 0;
  Resources res(drmModeGetResources(fd));
  if (!res) {
    why = "render-only device, no KMS";
    return false;
  }
  Connector conn;
  std::string states;
  for (int i = 0; i < res->count_connectors && !conn; ++i) {
    Connector c(drmModeGetConnector(fd, res->connectors[i]));
    if (!c) continue;
    states +=
        (states.empty() ? "" : ", ") + connector_name(*c) + " " + connection_name(c->connection);
    if (c->connection == DRM_MODE_CONNECTED && c->count_modes > 0) conn = std::move(c);
  }
  if (!conn) {
    why = states.empty() ? "no connectors" : "nothing connected (" + states + ")";
    return false;
  }
  const std::string name = connector_name(*conn);
  uint32_t crtc_id = 0;
  const int crtc_index = pick_crtc(fd, *res, *conn, crtc_id);
  if (crtc_index < 0) {
    why = "no CRTC can drive " + name;
    return false;
  }

  // The CRTC's primary plane, and whether it scans out `format`.
  uint32_t plane_id = 0;
  bool format_ok = !universal;  // legacy: the CRTC takes what AddFB2 accepted
  if (universal) {
    PlaneRes planes(drmModeGetPlaneResources(fd));
    for (uint32_t i = 0; planes && i < planes->count_planes && !plane_id; ++i) {
      Plane p(drmModeGetPlane(fd, planes->planes[i]));
      if (!p || !(p->possible_crtcs & (1u << crtc_index))) continue;
      uint64_t type = 0;
      if (!PropertyTable(fd, p->plane_id, DRM_MODE_OBJECT_PLANE).value("type", type) ||
          type != DRM_PLANE_TYPE_PRIMARY)
        continue;
      plane_id = p->plane_id;
      for (uint32_t f = 0; f < p->count_formats; ++f) format_ok |= p->formats[f] == format;
    }
    if (!plane_id) format_ok = true;  // no plane list: let the legacy path try
  }
  if (!format_ok) {
    why = "the primary plane of " + name + " cannot show XRGB8888";
    return false;
  }

  out.connector_id = conn->connector_id;
  out.connector_name = name;
  out.crtc_id = crtc_id;
  out.plane_id = plane_id;
  out.mode = choose_mode(conn->modes, conn->count_modes, options, name);
  uint64_t cap = 0;
  out.addfb2_modifiers = drmGetCap(fd, DRM_CAP_ADDFB2_MODIFIERS, &cap) == 0 && cap;
  out.modifiers.clear();
  if (plane_id) out.modifiers = plane_modifiers(fd, plane_id, format);
  out.props = KmsPropertyIds{};
  out.atomic = false;

  const char* legacy_env = std::getenv("CANDELA_DRM_LEGACY");
  const bool force_legacy = legacy_env && *legacy_env && std::strcmp(legacy_env, "0") != 0;
  if (force_legacy) {
    LOG_INFO("drm: CANDELA_DRM_LEGACY set: using legacy modesetting");
  } else if (!plane_id) {
    LOG_INFO("drm: no universal planes: using legacy modesetting");
  } else if (drmSetClientCap(fd, DRM_CLIENT_CAP_ATOMIC, 1) != 0) {
    LOG_INFO("drm: %s has no atomic modesetting: using legacy modesetting", out.driver.c_str());
  } else {
    KmsPropertyIds& p = out.props;
    PropertyTable c(fd, conn->connector_id, DRM_MODE_OBJECT_CONNECTOR);
    p.connector_crtc_id = c.id("CRTC_ID");
    PropertyTable cr(fd, crtc_id, DRM_MODE_OBJECT_CRTC);
    p.crtc_mode_id = cr.id("MODE_ID");
    p.crtc_active = cr.id("ACTIVE");
    PropertyTable pl(fd, plane_id, DRM_MODE_OBJECT_PLANE);
    p.plane_fb_id = pl.id("FB_ID");
    p.plane_crtc_id = pl.id("CRTC_ID");
    p.plane_src_x = pl.id("SRC_X");
    p.plane_src_y = pl.id("SRC_Y");
    p.plane_src_w = pl.id("SRC_W");
    p.plane_src_h = pl.id("SRC_H");
    p.plane_crtc_x = pl.id("CRTC_X");
    p.plane_crtc_y = pl.id("CRTC_Y");
    p.plane_crtc_w = pl.id("CRTC_W");
    p.plane_crtc_h = pl.id("CRTC_H");
    out.atomic = p.complete();
    if (!out.atomic) LOG_WARN("drm: atomic properties missing: falling back to legacy modesetting");
  }
  LOG_INFO("drm: %s (%s), connector %s, mode %s, CRTC %u, plane %u, %s", out.device.c_str(),
           out.driver.c_str(), name.c_str(), describe_mode(out.mode).c_str(), crtc_id, plane_id,
           out.atomic ? "atomic" : "legacy");
  return true;
}

KmsOutput open_kms_output(const DisplayOptions& options, uint32_t format, bool wait_for_screen) {
  std::vector<std::string> devices;
  if (!options.drm_device.empty()) {
    devices.push_back(options.drm_device);
  } else {
    if (DIR* dir = opendir("/dev/dri")) {
      while (dirent* e = readdir(dir))
        if (std::strncmp(e->d_name, "card", 4) == 0)
          devices.push_back(std::string("/dev/dri/") + e->d_name);
      closedir(dir);
    }
    // card10 after card9; the order of cards is not stable across boots anyway
    // (a Pi's v3d and vc4 swap places), so every card is looked at.
    std::sort(devices.begin(), devices.end(), [](const std::string& a, const std::string& b) {
      return a.size() != b.size() ? a.size() < b.size() : a < b;
    });
    if (devices.empty())
      throw RuntimeError(
          "drm: no /dev/dri/card* device (is a KMS driver loaded? On a Raspberry Pi: "
          "dtoverlay=vc4-kms-v3d)");
  }

  std::string tried;
  std::optional<KmsOutput> waiting;  // the first KMS card with nothing connected, DRM master
  for (const std::string& path : devices) {
    Fd fd(open(path.c_str(), O_RDWR | O_CLOEXEC));
    if (fd.get() < 0) {
      const int e = errno;
      tried += "\n  " + path + ": " + std::strerror(e) +
               (e == EACCES ? " (add the user to the 'video' group)" : "");
      LOG_INFO("drm: skipping %s: %s", path.c_str(), std::strerror(e));
      continue;
    }
    std::unique_ptr<drmVersion, VersionDeleter> version(drmGetVersion(fd.get()));
    if (!version) {
      tried += "\n  " + path + ": not a DRM device";
      LOG_INFO("drm: skipping %s: not a DRM device", path.c_str());
      continue;
    }
    KmsOutput out;
    out.device = path;
    out.driver = version->name ? version->name : "?";
    out.fd = fd.release();
    std::string why;
    const bool found = probe_kms_connector(out, options, format, why);
    const bool no_screen = !found && why.rfind("nothing connected", 0) == 0;
    if (!found && !(no_screen && wait_for_screen && !waiting)) {
      tried += "\n  " + path + " (" + out.driver + "): " + why;
      LOG_INFO("drm: skipping %s (%s): %s", path.c_str(), out.driver.c_str(), why.c_str());
      continue;
    }
    // Since Linux 5.8 the first opener is master; otherwise someone else
    // (a desktop, another kiosk) holds the display.
    if (!drmIsMaster(out.fd) && drmSetMaster(out.fd) != 0) {
      const int e = errno;
      tried += "\n  " + path + ": cannot become DRM master (" + std::strerror(e) +
               "): another program (a desktop, another candela) is showing on it";
      LOG_INFO("drm: skipping %s: cannot become DRM master", path.c_str());
      continue;
    }
    if (found) return out;
    tried += "\n  " + path + " (" + out.driver + "): " + why;
    LOG_INFO("drm: %s (%s): %s", path.c_str(), out.driver.c_str(), why.c_str());
    waiting.emplace(std::move(out));
  }
  if (waiting) return std::move(*waiting);
  throw RuntimeError(card_list_error(tried));
}

}  // namespace candela
