#include "display/drm_master.h"

#include <xf86drm.h>

#include <algorithm>
#include <cstring>
#include <thread>

#include "core/log.h"

namespace candela {

void DrmMaster::lose(int e) {
  lost_ = true;
  lost_since_ = Clock::now();
  retry_ms_ = kFirstRetryMs;
  next_retry_ = lost_since_ + std::chrono::milliseconds(retry_ms_);
  ++times_lost_;
  LOG_WARN(
      "drm: lost the display on %s (%s: another program holds DRM master): pausing, asking for "
      "it again at most %d ms apart",
      out_.connector_name.c_str(), std::strerror(e), kMaxRetryMs);
}

bool DrmMaster::try_resume(DrmCommit& commit, uint32_t fb, int w, int h) {
  const auto now = Clock::now();
  if (now < next_retry_) return false;
  if ((drmIsMaster(out_.fd) || drmSetMaster(out_.fd) == 0) && commit.modeset(fb, w, h)) {
    lost_ = false;
    LOG_INFO("drm: DRM master is back after %.1f s: presenting on %s again",
             std::chrono::duration<double>(now - lost_since_).count(), out_.connector_name.c_str());
    return true;
  }
  retry_ms_ = std::min(retry_ms_ * 2, kMaxRetryMs);
  next_retry_ = now + std::chrono::milliseconds(retry_ms_);
  return false;
}

void DrmMaster::wait_for_retry() const { std::this_thread::sleep_until(next_retry_); }

}  // namespace candela
