// The lock-free handoff from the frame loop to the audio thread: a bounded
// single-producer single-consumer ring of SoundCues (one per animation step).
// push/pop never lock or allocate; either side may sleep on a futex
// (std::atomic wait) when the ring is full or empty, which only a recording
// does (it must not drop a step); the live output never waits in the frame loop.
#pragma once

#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>

#include "sound/sound_cue.h"

namespace candela {

class CueRing {
 public:
  static constexpr uint32_t kCapacity = 256;  // ~4 s at 60 steps/s

  bool try_push(const SoundCue& cue) {
    const uint32_t head = head_.load(std::memory_order_relaxed);
    if (head - tail_.load(std::memory_order_acquire) == kCapacity) return false;
    slots_[head % kCapacity] = cue;
    head_.store(head + 1, std::memory_order_release);
    wake_.fetch_add(1, std::memory_order_acq_rel);
    wake_.notify_one();
    return true;
  }
  // Waits (futex) while the ring is full.
  void push(const SoundCue& cue) {
    while (!try_push(cue)) {
      const uint32_t tail = tail_.load(std::memory_order_acquire);
      if (head_.load(std::memory_order_relaxed) - tail == kCapacity)
        tail_.wait(tail, std::memory_order_acquire);
    }
  }
  bool try_pop(SoundCue& out) {
    const uint32_t tail = tail_.load(std::memory_order_relaxed);
    if (tail == head_.load(std::memory_order_acquire)) return false;
    out = slots_[tail % kCapacity];
    tail_.store(tail + 1, std::memory_order_release);
    tail_.notify_one();
    return true;
  }
  // Consumer: waits (futex) until a cue is there or close() was called;
  // false once closed and drained.
  bool pop(SoundCue& out) {
    for (;;) {
      // Read the wake count first: a push or close after this changes it, so
      // the wait below cannot miss one.
      const uint32_t wake = wake_.load(std::memory_order_acquire);
      if (try_pop(out)) return true;
      if (closed_.load(std::memory_order_acquire)) return try_pop(out);
      wake_.wait(wake, std::memory_order_acquire);
    }
  }
  // Producer: no more cues. Wakes a waiting consumer.
  void close() {
    closed_.store(true, std::memory_order_release);
    wake_.fetch_add(1, std::memory_order_acq_rel);
    wake_.notify_all();
  }
  uint32_t size() const {
    return head_.load(std::memory_order_acquire) - tail_.load(std::memory_order_acquire);
  }

 private:
  alignas(64) std::atomic<uint32_t> head_{0};
  alignas(64) std::atomic<uint32_t> tail_{0};
  alignas(64) std::atomic<uint32_t> wake_{0};  // bumped by every push and by close()
  std::atomic<bool> closed_{false};
  std::array<SoundCue, kCapacity> slots_{};
};

}  // namespace candela
