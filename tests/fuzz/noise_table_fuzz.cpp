// libFuzzer target for the noise-table reader (`candela-tool noise` files, as
// scenes name them in `*_table` keys): any byte string must either be refused
// with a ConfigError or parse as a table whose every sample, interpolated
// position and period the candle rig and the wind read without going out of
// range (samples are Q0.16 fractions of [0, 1]).
//   build with clang: ninja -C build-fuzz noise_table_fuzz (tests/fuzz/run-fuzz.sh)
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"
#include "core/noise_table.h"

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
    // What parse accepts, serialize writes back byte for byte.
    if (NoiseTable::serialize(t.info(), t.samples()) != bytes) __builtin_trap();
  } catch (const ConfigError&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using candela::NoiseTable;
  const std::string_view in(reinterpret_cast<const char*>(data), size);
  check(in);
  // The checksum hides everything after it from the fuzzer: try the input
  // again with the checksum its samples would have.
  if (size >= NoiseTable::kHeaderBytes && (size - NoiseTable::kHeaderBytes) % 2 == 0) {
    std::string fixed(in);
    std::vector<uint16_t> samples((size - NoiseTable::kHeaderBytes) / 2);
    for (size_t i = 0; i < samples.size(); ++i)
      samples[i] = static_cast<uint16_t>(data[NoiseTable::kHeaderBytes + 2 * i] |
                                         (data[NoiseTable::kHeaderBytes + 2 * i + 1] << 8));
    const uint32_t sum = NoiseTable::checksum(samples);
    for (int b = 0; b < 4; ++b) fixed[32 + b] = static_cast<char>((sum >> (8 * b)) & 0xFF);
    check(fixed);
  }
  return 0;
}
