// Once running, the audio threads allocate nothing: every operator new and
// every malloc/calloc/realloc in the process (ALSA's C code included) is
// counted while the ALSA thread plays (ALSA's `null` device) or the
// recording thread writes, and the test thread only pushes cues. As
// tests/app/no_allocation_test.cpp does for the frame loop.
#include <gtest/gtest.h>

#include <atomic>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <new>
#include <string>
#include <thread>

#include "sound/sound_output.h"

namespace {
std::atomic<bool> g_counting{false};
std::atomic<long> g_allocations{0};
[[maybe_unused]] void count() {
  if (g_counting.load(std::memory_order_relaxed))
    g_allocations.fetch_add(1, std::memory_order_relaxed);
}
}  // namespace

#if !defined(__SANITIZE_ADDRESS__)
extern "C" {
void* __libc_malloc(size_t);
void* __libc_calloc(size_t, size_t);
void* __libc_realloc(void*, size_t);
void* malloc(size_t n) {
  count();
  return __libc_malloc(n);
}
void* calloc(size_t n, size_t k) {
  count();
  return __libc_calloc(n, k);
}
void* realloc(void* p, size_t n) {
  count();
  return __libc_realloc(p, n);
}
}
void* operator new(std::size_t n) {
  count();
  if (void* p = __libc_malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
#endif

namespace candela {
namespace {

SoundCue busy_cue(uint64_t i) {
  SoundCue c;
  c.fire = Fixed::from_int(2);
  c.activity = Fixed::from_int(3);  // many crackles: every voice path runs
  c.wind = Fixed::from_int(static_cast<int32_t>((i / 60) % 4));
  c.blowouts = i % 90 == 0;
  c.sputters = 2;
  c.volume = (i / 30) % 2 ? 0.9f : 0.2f;  // `volume` commands: the gain glides now and then
  return c;
}

// The counter itself: C++ and C allocations (as ALSA would make) both count.
TEST(SoundThreads, CounterSeesAllocations) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "allocation counting needs the plain allocator";
#endif
  g_allocations = 0;
  g_counting = true;
  int* volatile p = new int(1);
  char* volatile q = strdup("x");
  g_counting = false;
  delete p;
  std::free(q);
  EXPECT_EQ(g_allocations.load(), 2);
}

TEST(SoundThreads, AlsaThreadAllocatesNothingOnceRunning) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "allocation counting needs the plain allocator";
#endif
  SoundSettings s;
  s.enabled = true;
  s.device = "null";
  auto out = open_sound_device(s, 60, 3);
  uint64_t i = 0;
  while (out->stats().periods < 20) out->push(busy_cue(i++));  // warm-up: the device opened
  ASSERT_TRUE(out->stats().device_open);
  const uint64_t from = out->stats().periods;
  g_allocations = 0;
  g_counting = true;
  while (out->stats().periods < from + 500) {  // 10 s of sound
    out->push(busy_cue(i++));
    std::this_thread::yield();
  }
  g_counting = false;
  const long allocations = g_allocations.load();
  out->finish();
  EXPECT_EQ(allocations, 0) << "allocations while the ALSA thread played 500 periods";
}

TEST(SoundThreads, RecordingThreadAllocatesNothingOnceRunning) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "allocation counting needs the plain allocator";
#endif
  SoundSettings s;
  s.enabled = true;
  const std::string path = ::testing::TempDir() + "candela-sound-alloc.wav";
  auto rec = open_sound_recording(s, 60, 3, path);
  uint64_t i = 0;
  for (; i < 60; ++i) rec->push(busy_cue(i));
  while (rec->stats().steps < 60) std::this_thread::yield();  // warm-up written (stdio's buffer)
  g_allocations = 0;
  g_counting = true;
  for (; i < 60 + 1200; ++i) rec->push(busy_cue(i));
  while (rec->stats().steps < i) std::this_thread::yield();
  g_counting = false;
  const long allocations = g_allocations.load();
  rec->finish();
  std::remove(path.c_str());
  EXPECT_EQ(allocations, 0) << "allocations while 20 s of sound were recorded";
}

}  // namespace
}  // namespace candela
