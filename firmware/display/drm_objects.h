// The KMS objects the display backend looks at, held and read safely: owning
// handles for libdrm's allocations (freed with the right drmModeFree*), an
// owned file descriptor, property lookup by name, the CRTC that can drive a
// connector, and the modifiers a plane scans out. Internal to display/.
#pragma once

#include <unistd.h>
#include <xf86drm.h>
#include <xf86drmMode.h>

#include <cstdint>
#include <cstring>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace candela::drm {

struct ResourcesDeleter {
  void operator()(drmModeRes* p) const { drmModeFreeResources(p); }
};
struct ConnectorDeleter {
  void operator()(drmModeConnector* p) const { drmModeFreeConnector(p); }
};
struct EncoderDeleter {
  void operator()(drmModeEncoder* p) const { drmModeFreeEncoder(p); }
};
struct PlaneResDeleter {
  void operator()(drmModePlaneRes* p) const { drmModeFreePlaneResources(p); }
};
struct PlaneDeleter {
  void operator()(drmModePlane* p) const { drmModeFreePlane(p); }
};
struct PropsDeleter {
  void operator()(drmModeObjectProperties* p) const { drmModeFreeObjectProperties(p); }
};
struct PropDeleter {
  void operator()(drmModePropertyRes* p) const { drmModeFreeProperty(p); }
};
struct BlobDeleter {
  void operator()(drmModePropertyBlobRes* p) const { drmModeFreePropertyBlob(p); }
};
struct VersionDeleter {
  void operator()(drmVersion* p) const { drmFreeVersion(p); }
};
using Resources = std::unique_ptr<drmModeRes, ResourcesDeleter>;
using Connector = std::unique_ptr<drmModeConnector, ConnectorDeleter>;
using Encoder = std::unique_ptr<drmModeEncoder, EncoderDeleter>;
using PlaneRes = std::unique_ptr<drmModePlaneRes, PlaneResDeleter>;
using Plane = std::unique_ptr<drmModePlane, PlaneDeleter>;
using ObjectProps = std::unique_ptr<drmModeObjectProperties, PropsDeleter>;
using Property = std::unique_ptr<drmModePropertyRes, PropDeleter>;
using Blob = std::unique_ptr<drmModePropertyBlobRes, BlobDeleter>;

class Fd {
 public:
  explicit Fd(int fd) : fd_(fd) {}
  ~Fd() {
    if (fd_ >= 0) close(fd_);
  }
  Fd(const Fd&) = delete;
  Fd& operator=(const Fd&) = delete;
  int get() const { return fd_; }
  int release() { return std::exchange(fd_, -1); }

 private:
  int fd_;
};

// e.g. HDMI-A-1, Virtual-1
std::string connector_name(const drmModeConnector& c);
// connected, disconnected, unknown
const char* connection_name(drmModeConnection c);

// Looks up property ids (and optionally a value) of one KMS object by name.
class PropertyTable {
 public:
  PropertyTable(int fd, uint32_t object, uint32_t type)
      : fd_(fd), props_(drmModeObjectGetProperties(fd, object, type)) {}
  uint32_t id(const char* name) const { return find(name, nullptr); }
  bool value(const char* name, uint64_t& out) const { return find(name, &out) != 0; }

 private:
  uint32_t find(const char* name, uint64_t* value) const {
    if (!props_) return 0;
    for (uint32_t i = 0; i < props_->count_props; ++i) {
      Property p(drmModeGetProperty(fd_, props_->props[i]));
      if (p && std::strcmp(p->name, name) == 0) {
        if (value) *value = props_->prop_values[i];
        return p->prop_id;
      }
    }
    return 0;
  }
  int fd_;
  ObjectProps props_;
};

// The CRTC to drive the connector with: the one already driving it if any,
// else the first one an encoder of the connector can use. Its index in
// res.crtcs, its id in crtc_id; -1 when none can.
int pick_crtc(int fd, const drmModeRes& res, const drmModeConnector& conn, uint32_t& crtc_id);

// The modifiers the plane's IN_FORMATS blob lists for `format`.
std::vector<uint64_t> plane_modifiers(int fd, uint32_t plane_id, uint32_t format);

}  // namespace candela::drm
