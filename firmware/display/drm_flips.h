// The page flips of one KMS output (the DRM display's): at most one in
// flight; the buffer on screen and the one queued, each given back to GBM
// when a flip or modeset retires it; and the vblanks missed between flips,
// read from the flip events' vblank counter.
#pragma once

#include <gbm.h>
#include <xf86drm.h>

#include <cstdint>

#include "display/drm_kms.h"
#include "display/drm_scanout.h"

namespace candela {

class DrmFlips {
 public:
  DrmFlips(const KmsOutput& out, DrmScanout& scanout);
  DrmFlips(const DrmFlips&) = delete;
  DrmFlips& operator=(const DrmFlips&) = delete;

  // A flip to `bo` was queued with this object as the event's user data.
  void queued(gbm_bo* bo) {
    flip_pending_ = true;
    pending_ = bo;
  }
  // `bo` is on screen by a modeset: the old front buffer goes back to GBM.
  void shown(gbm_bo* bo);
  // Waits for the flip in flight. False (errno EACCES) when it never
  // completed because another program took DRM master meanwhile (its buffer
  // given back); throws RuntimeError on any other failure.
  bool wait();
  // The vblank counter jumps (the screen was off, a new mode): the next
  // flip counts no missed vblanks.
  void resync() { resync_sequence_ = true; }
  // Every buffer back to GBM (before its surface goes).
  void release_all();

  uint64_t done() const { return flips_done_; }
  int64_t missed() const { return missed_; }

 private:
  static void on_page_flip(int, unsigned sequence, unsigned, unsigned, void* data);

  const KmsOutput& out_;
  DrmScanout& scanout_;
  drmEventContext event_context_{};
  gbm_bo* front_ = nullptr;    // on screen
  gbm_bo* pending_ = nullptr;  // queued to flip at the next vblank
  bool flip_pending_ = false;
  bool resync_sequence_ = false;
  uint64_t flips_done_ = 0;
  uint32_t last_sequence_ = 0;
  int64_t missed_ = 0;
};

}  // namespace candela
