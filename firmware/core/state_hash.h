// A 64-bit hash of animation state (Scene::hash_state, Element::hash_state):
// fed the fixed-point values (and the few floats derived from them) one by
// one, so two builds -- amd64 and arm64, say -- can show that their
// animation is bit-identical without dumping it (tests/arm64). FNV-1a over
// 64-bit words, then a splitmix64 finaliser. Never on the frame loop's path:
// only tools and tests call it.
#pragma once

#include <bit>
#include <cstdint>
#include <span>

#include "core/fixed.h"

namespace candela {

class StateHash {
 public:
  void add(uint64_t v) {
    h_ ^= v;
    h_ *= 0x100000001b3ULL;
  }
  void add(int64_t v) { add(static_cast<uint64_t>(v)); }
  void add(uint32_t v) { add(static_cast<uint64_t>(v)); }
  void add(int32_t v) { add(static_cast<uint64_t>(static_cast<int64_t>(v))); }
  void add(bool v) { add(static_cast<uint64_t>(v)); }
  void add(Fixed v) { add(v.raw); }
  void add(float v) { add(static_cast<uint64_t>(std::bit_cast<uint32_t>(v))); }
  void add(double v) { add(std::bit_cast<uint64_t>(v)); }
  template <class T>
  void add(std::span<const T> values) {
    add(static_cast<uint64_t>(values.size()));
    for (const T& v : values) add(v);
  }

  uint64_t value() const {
    uint64_t z = h_ + 0x9e3779b97f4a7c15ULL;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }

 private:
  uint64_t h_ = 0xcbf29ce484222325ULL;
};

}  // namespace candela
