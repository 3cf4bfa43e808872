// An atomic KMS request in fixed storage, committed with the ioctl itself:
// libdrm's drmModeAtomicCommit copies and sorts the request on the heap on
// every call, and a frame must not allocate. Properties of one object are
// added together (the kernel takes them grouped by object). Used by the DRM
// display's atomic path (drm_atomic.cpp).
#pragma once

#include <cstdint>

namespace candela {

class AtomicRequest {
 public:
  void clear() {
    objects_ = 0;
    props_ = 0;
  }
  // False when the request is full (it is sized for one connector, CRTC and plane).
  bool add(uint32_t object, uint32_t property, uint64_t value) {
    if (props_ == kMaxProps) return false;
    if (objects_ == 0 || object_ids_[objects_ - 1] != object) {
      if (objects_ == kMaxObjects) return false;
      object_ids_[objects_] = object;
      counts_[objects_++] = 0;
    }
    ++counts_[objects_ - 1];
    prop_ids_[props_] = property;
    values_[props_++] = value;
    return true;
  }
  // 0 or -1 with errno set, like libdrm.
  int commit(int fd, uint32_t flags, void* user_data);

 private:
  static constexpr uint32_t kMaxObjects = 4, kMaxProps = 24;
  uint32_t objects_ = 0, props_ = 0;
  uint32_t object_ids_[kMaxObjects] = {}, counts_[kMaxObjects] = {};
  uint32_t prop_ids_[kMaxProps] = {};
  uint64_t values_[kMaxProps] = {};
};

}  // namespace candela
