#include "flame_drivers/no_repeat_guard.h"

#include <algorithm>

#include "core/random.h"

namespace candela {
namespace {
uint64_t mix(uint64_t h, uint64_t v) {
  // SplitMix64-style finaliser over a running state: cheap and well spread.
  h ^= v + kSplitMix64Gamma + (h << 6) + (h >> 2);
  return splitmix64_mix(h);
}
}  // namespace

NoRepeatGuard::NoRepeatGuard(int max_stretch, int window)
    : max_stretch_(std::max(1, max_stretch)),
      window_(std::max(1, window)),
      recent_(static_cast<size_t>(max_stretch_), -1),
      ended_(static_cast<size_t>(window_), 0) {
  size_t cap = 16;
  while (cap < 2 * static_cast<size_t>(window_)) cap *= 2;
  table_.resize(cap);
  mask_ = cap - 1;
}

void NoRepeatGuard::clear() {
  std::fill(recent_.begin(), recent_.end(), -1);
  std::fill(ended_.begin(), ended_.end(), 0);
  std::fill(table_.begin(), table_.end(), Slot{});
  pushed_ = 0;
}

uint64_t NoRepeatGuard::stretch_hash(int32_t next) const {
  const size_t l = recent_.size();
  uint64_t h = 0x5EEDF1A3E5ULL;
  for (size_t i = 0; i < l; ++i)  // oldest first
    h = mix(h, static_cast<uint32_t>(recent_[(pushed_ + i) % l]));
  h = mix(h, static_cast<uint32_t>(next));
  return h | 1;  // 0 marks an empty slot
}

bool NoRepeatGuard::contains(uint64_t h) const {
  for (uint64_t i = h & mask_;; i = (i + 1) & mask_) {
    if (table_[i].count == 0) return false;
    if (table_[i].hash == h) return true;
  }
}

void NoRepeatGuard::insert(uint64_t h) {
  uint64_t i = h & mask_;
  while (table_[i].count != 0 && table_[i].hash != h) i = (i + 1) & mask_;
  table_[i].hash = h;
  ++table_[i].count;
}

void NoRepeatGuard::erase(uint64_t h) {
  uint64_t i = h & mask_;
  while (table_[i].hash != h || table_[i].count == 0) {
    if (table_[i].count == 0) return;  // not present (cannot happen)
    i = (i + 1) & mask_;
  }
  if (--table_[i].count != 0) return;
  // Backward-shift deletion keeps linear probing correct without tombstones.
  uint64_t hole = i;
  for (uint64_t j = (hole + 1) & mask_; table_[j].count != 0; j = (j + 1) & mask_) {
    const uint64_t home = table_[j].hash & mask_;
    // Move j into the hole if its home is not cyclically in (hole, j].
    const bool stays = hole <= j ? (home > hole && home <= j) : (home > hole || home <= j);
    if (!stays) {
      table_[hole] = table_[j];
      table_[j] = Slot{};
      hole = j;
    }
  }
  table_[hole] = Slot{};
}

bool NoRepeatGuard::allows(int32_t next) const {
  if (pushed_ < recent_.size()) return true;  // no full stretch yet
  return !contains(stretch_hash(next));
}

void NoRepeatGuard::push(int32_t frame) {
  const size_t w = ended_.size();
  const size_t slot = pushed_ % w;
  // The stretch that ended W steps ago leaves the window.
  if (ended_[slot] != 0) erase(ended_[slot]);
  ended_[slot] = 0;
  if (pushed_ >= recent_.size()) {
    const uint64_t h = stretch_hash(frame);
    ended_[slot] = h;
    insert(h);
  }
  recent_[pushed_ % recent_.size()] = frame;
  ++pushed_;
}

}  // namespace candela
