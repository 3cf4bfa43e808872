#include "core/noise_table.h"

#include <cstring>

#include "core/error.h"
#include "core/file_read.h"

namespace candela {
namespace {

constexpr char kMagic[8] = {'C', 'N', 'D', 'L', 'N', 'O', 'I', 'S'};

uint32_t get_u32(std::string_view b, size_t at) {
  uint32_t v = 0;
  for (int i = 3; i >= 0; --i) v = (v << 8) | static_cast<uint8_t>(b[at + i]);
  return v;
}
uint64_t get_u64(std::string_view b, size_t at) {
  return get_u32(b, at) | (static_cast<uint64_t>(get_u32(b, at + 4)) << 32);
}
void put_u32(std::string& s, uint32_t v) {
  for (int i = 0; i < 4; ++i) s.push_back(static_cast<char>((v >> (8 * i)) & 0xFF));
}
void put_u64(std::string& s, uint64_t v) {
  put_u32(s, static_cast<uint32_t>(v));
  put_u32(s, static_cast<uint32_t>(v >> 32));
}
bool is_pow2(uint32_t n) { return n && !(n & (n - 1)); }

}  // namespace

uint32_t NoiseTable::checksum(std::span<const uint16_t> samples) {
  uint32_t h = 2166136261u;
  for (uint16_t s : samples) {
    for (int k = 0; k < 2; ++k) {
      h ^= (s >> (8 * k)) & 0xFFu;
      h *= 16777619u;
    }
  }
  return h;
}

std::string NoiseTable::serialize(const NoiseTableInfo& info, std::span<const uint16_t> samples) {
  std::string s(kMagic, sizeof kMagic);
  put_u32(s, kVersion);
  put_u32(s, static_cast<uint32_t>(samples.size()));
  put_u32(s, static_cast<uint32_t>(info.beta_milli));
  put_u32(s, info.gust ? 1u : 0u);
  put_u64(s, info.seed);
  put_u32(s, checksum(samples));
  put_u32(s, 0);
  for (uint16_t v : samples) {
    s.push_back(static_cast<char>(v & 0xFF));
    s.push_back(static_cast<char>(v >> 8));
  }
  return s;
}

NoiseTable NoiseTable::parse(std::string_view b, const std::string& source) {
  auto fail = [&](const char* field, const std::string& expected) {
    throw ConfigError(source, field, expected);
  };
  if (b.size() < kHeaderBytes)
    fail("header", "expected at least " + std::to_string(kHeaderBytes) +
                       " bytes of noise-table header, got " + std::to_string(b.size()) +
                       " bytes (truncated?)");
  if (std::memcmp(b.data(), kMagic, sizeof kMagic) != 0)
    fail("magic", "expected \"CNDLNOIS\" (a candela-tool noise table)");
  NoiseTable t;
  t.info_.version = get_u32(b, 8);
  if (t.info_.version != kVersion)
    fail("version", "expected " + std::to_string(kVersion) + ", got " +
                        std::to_string(t.info_.version) + " (made by a different candela-tool?)");
  t.info_.length = get_u32(b, 12);
  if (!is_pow2(t.info_.length) || t.info_.length < kMinLength || t.info_.length > kMaxLength)
    fail("length", "expected a power of two in [16, 65536], got " + std::to_string(t.info_.length));
  t.info_.beta_milli = static_cast<int32_t>(get_u32(b, 16));
  if (t.info_.beta_milli < 0 || t.info_.beta_milli > 10000)
    fail("beta", "expected beta in [0, 10], got " + std::to_string(t.info_.beta_milli / 1000.0));
  const uint32_t flags = get_u32(b, 20);
  if (flags & ~1u) fail("flags", "expected only bit 0 (gust) set, got " + std::to_string(flags));
  t.info_.gust = flags & 1u;
  t.info_.seed = get_u64(b, 24);
  const uint32_t sum = get_u32(b, 32);
  if (get_u32(b, 36) != 0) fail("reserved", "expected 0");
  const size_t want = kHeaderBytes + 2 * static_cast<size_t>(t.info_.length);
  if (b.size() != want)
    fail("samples", "expected " + std::to_string(want) + " bytes for " +
                        std::to_string(t.info_.length) + " samples, got " +
                        std::to_string(b.size()));
  t.samples_.resize(t.info_.length);
  for (uint32_t i = 0; i < t.info_.length; ++i)
    t.samples_[i] = static_cast<uint16_t>(static_cast<uint8_t>(b[kHeaderBytes + 2 * i]) |
                                          (static_cast<uint8_t>(b[kHeaderBytes + 2 * i + 1]) << 8));
  if (checksum(t.samples_) != sum)
    fail("checksum", "expected the sample bytes to match (corrupt file?)");
  t.mask_ = t.info_.length - 1;
  return t;
}

NoiseTable NoiseTable::load(const std::string& path) {
  return parse(read_bounded_file(path, FileKind::kNoiseTable), path);
}

}  // namespace candela
