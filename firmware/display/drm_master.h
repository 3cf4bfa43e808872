// Losing and regaining DRM master (the DRM display's). Another program (a
// VT switch through logind, a second compositor, a debugging tool) took
// master: nothing can be shown until it gives it back. Candela keeps running
// (animation, inputs, control socket), renders at the retry rate and asks
// for master again after 50 ms, then less and less often, at most 500 ms
// apart.
#pragma once

#include <chrono>
#include <cstdint>

#include "display/drm_commit.h"
#include "display/drm_kms.h"

namespace candela {

class DrmMaster {
 public:
  static constexpr int kFirstRetryMs = 50, kMaxRetryMs = 500;

  explicit DrmMaster(const KmsOutput& out) : out_(out) {}

  // A commit failed with errno `e` (is_master_error): nothing shown from now.
  void lose(int e);
  bool lost() const { return lost_; }
  // When a retry is due: master again and the mode set with framebuffer fb
  // (w x h) shows it: true. False: not yet (ask again later).
  bool try_resume(DrmCommit& commit, uint32_t fb, int w, int h);
  // Paced by the retries while nothing is shown (no vblank to wait for).
  void wait_for_retry() const;
  uint64_t times_lost() const { return times_lost_; }

 private:
  using Clock = std::chrono::steady_clock;
  const KmsOutput& out_;
  bool lost_ = false;
  int retry_ms_ = kFirstRetryMs;
  uint64_t times_lost_ = 0;
  Clock::time_point lost_since_{}, next_retry_{};
};

}  // namespace candela
