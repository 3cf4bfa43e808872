#include "display/drm_flips.h"

#include <poll.h>

#include <cerrno>
#include <cstring>
#include <string>

#include "core/error.h"

namespace candela {
namespace {
constexpr int kFlipTimeoutMs = 2000;
}

DrmFlips::DrmFlips(const KmsOutput& out, DrmScanout& scanout) : out_(out), scanout_(scanout) {
  event_context_.version = 2;
  event_context_.page_flip_handler = &DrmFlips::on_page_flip;
}

void DrmFlips::shown(gbm_bo* bo) {
  if (front_) scanout_.release(front_);
  front_ = bo;
}

bool DrmFlips::wait() {
  while (flip_pending_) {
    pollfd p{out_.fd, POLLIN, 0};
    const int r = poll(&p, 1, kFlipTimeoutMs);
    if (r < 0) {
      if (errno == EINTR) continue;
      throw RuntimeError("drm: poll on " + out_.device + " failed: " + std::strerror(errno));
    }
    if (r == 0) {
      flip_pending_ = false;  // do not wait for it again
      if (!drmIsMaster(out_.fd)) {
        if (pending_) scanout_.release(pending_);
        pending_ = nullptr;
        errno = EACCES;
        return false;
      }
      throw RuntimeError("drm: a page flip did not complete within " +
                         std::to_string(kFlipTimeoutMs) + " ms");
    }
    if (drmHandleEvent(out_.fd, &event_context_) != 0)
      throw RuntimeError("drm: reading DRM events failed: " + std::string(std::strerror(errno)));
  }
  return true;
}

void DrmFlips::on_page_flip(int, unsigned sequence, unsigned, unsigned, void* data) {
  auto* self = static_cast<DrmFlips*>(data);
  self->flip_pending_ = false;
  if (self->front_) self->scanout_.release(self->front_);
  self->front_ = self->pending_;
  self->pending_ = nullptr;
  // A gap of more than one in the vblank counter between flips means
  // vblanks went by showing an old frame.
  if (self->flips_done_ > 0 && !self->resync_sequence_) {
    const uint32_t gap = sequence - self->last_sequence_;
    if (gap > 1) self->missed_ += gap - 1;
  }
  self->last_sequence_ = sequence;
  self->resync_sequence_ = false;
  ++self->flips_done_;
}

void DrmFlips::release_all() {
  if (pending_) scanout_.release(pending_);
  if (front_) scanout_.release(front_);
  pending_ = front_ = nullptr;
}

}  // namespace candela
