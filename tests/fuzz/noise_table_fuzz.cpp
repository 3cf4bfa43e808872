// libFuzzer target for the noise-table reader (`candela-tool noise` files, as
// scenes name them in `*_table` keys; Candela container files, model_file.h):
// any byte string must either be refused with a ConfigError or parse as a
// table whose every sample, interpolated position and period the candle rig
// and the wind read without going out of range (samples are Q0.16 fractions
// of [0, 1]).
//   build with clang: ninja -C build-fuzz noise_table_fuzz (tests/fuzz/run-fuzz.sh)
#include <cstdint>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"
#include "model/model_file.h"
#include "model/noise_table.h"

namespace {

void check(std::string_view bytes) {
  using namespace candela;
  try {
    const NoiseTable t = NoiseTable::parse(bytes, "fuzz.cnoise");
    const uint32_t n = t.length();
    if (n < NoiseTable::kMinLength || n > NoiseTable::kMaxLength || (n & (n - 1)) != 0 ||
        t.samples().size() != n)
      __builtin_trap();  // parse let through a length the readers cannot index
    // Round the table as the rig does, at positions that straddle the wrap.
    const Fixed one = Fixed::from_int(1);
    for (uint32_t i = 0; i < 2 * n; ++i) {
      const uint32_t pos = i * 0x8000u + 0x7FFFu * (i & 1u);
      const Fixed v = t.at(pos), w = t.at_index(i);
      if (v < Fixed{} || v > one || w < Fixed{} || w > one) __builtin_trap();
    }
    // What parse accepts, serialize writes back as the same table, and
    // writing that again gives the same bytes (the canonical form).
    const std::string again = NoiseTable::serialize(t.info(), t.samples());
    const NoiseTable u = NoiseTable::parse(again, "again.cnoise");
    if (u.info().beta_milli != t.info().beta_milli || u.info().gust != t.info().gust ||
        u.info().seed != t.info().seed || u.length() != n ||
        !std::equal(u.samples().begin(), u.samples().end(), t.samples().begin()) ||
        NoiseTable::serialize(u.info(), u.samples()) != again)
      __builtin_trap();
  } catch (const ConfigError&) {
  }
}

// The input with the CRC-32 its header and data would have, or empty when
// it has no checksum entry to rewrite in place.
std::string with_fixed_checksum(std::string_view in) {
  if (in.size() < 8) return {};
  uint64_t hlen = 0;
  for (int i = 7; i >= 0; --i) hlen = (hlen << 8) | static_cast<uint8_t>(in[i]);
  if (hlen > in.size() - 8) return {};
  const std::string_view text = in.substr(8, hlen);
  nlohmann::json header = nlohmann::json::parse(text, nullptr, false);
  if (!header.is_object() || !header.contains("__metadata__") ||
      !header["__metadata__"].is_object())
    return {};
  header["__metadata__"].erase("checksum");
  const size_t at = text.find("\"crc32:");
  if (at == std::string_view::npos || at + 16 > text.size()) return {};
  const std::string_view data = in.substr(8 + hlen);
  const uint32_t crc = candela::model::model_checksum(
      header, reinterpret_cast<const uint8_t*>(data.data()), data.size());
  std::string out(in);
  char hex[9];
  std::snprintf(hex, sizeof hex, "%08x", crc);
  out.replace(8 + at + 7, 8, hex);
  return out;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view in(reinterpret_cast<const char*>(data), size);
  check(in);
  // The checksum hides everything after it from the fuzzer: try the input
  // again with the checksum its header and samples would have.
  const std::string fixed = with_fixed_checksum(in);
  if (!fixed.empty()) check(fixed);
  return 0;
}
