// Keeps a walk over flame frames from visibly looping: it remembers every
// stretch of L+1 consecutive frames shown in the last W steps and refuses a
// next frame that would show such a stretch again. In other words, no stretch
// longer than L frames is replayed within W frames.
//
// Stretches are kept as 64-bit hashes in a fixed-size open-addressing table
// (a multiset, so a stretch seen twice in the window is remembered until both
// copies leave). Equal stretches always hash equal, so nothing that repeats
// gets through; a hash collision can only make the guard refuse a step it
// could have allowed. Sized once; push() and allows() never allocate.
#pragma once

#include <cstdint>
#include <vector>

namespace candela {

class NoRepeatGuard {
 public:
  // max_stretch = L >= 1, window = W >= 1 steps.
  NoRepeatGuard(int max_stretch, int window);

  // Would showing `next` now replay a stretch longer than L within W steps?
  bool allows(int32_t next) const;
  void push(int32_t frame);
  void clear();

  int max_stretch() const { return max_stretch_; }
  int window() const { return window_; }

 private:
  uint64_t stretch_hash(int32_t next) const;  // the last L frames followed by `next`
  void insert(uint64_t h);
  void erase(uint64_t h);
  bool contains(uint64_t h) const;

  int max_stretch_, window_;
  std::vector<int32_t> recent_;  // ring: the last L frames
  std::vector<uint64_t> ended_;  // ring: hash of the stretch ending at each of the last W steps
  uint64_t pushed_ = 0;          // frames pushed since clear()
  struct Slot {
    uint64_t hash = 0;
    uint32_t count = 0;
  };
  std::vector<Slot> table_;  // power of two, at least 2 W
  uint64_t mask_ = 0;
};

}  // namespace candela
