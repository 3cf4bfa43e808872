// 1/f^beta noise tables, as made by `candela-tool noise`, read at run time.
// Samples are Q0.16 fractions of [0, 1]; reading interpolates in integers,
// so a table and a position give the same value on every machine.
//
// A table is a Candela container file (model/model_file.h: JSON header,
// 64-byte aligned tensors, CRC-32), read by the same reader as a model:
//   tensor "samples"  U16 [length], length a power of two in [16, 65536]
//   "model" info      {"kind": "noise-table", "version": 1,
//                      "beta_milli": beta * 1000 (what it was made with),
//                      "gust": true when the minimum was moved to index 0,
//                      "seed": the synthesis seed}
// The samples are copied out once at load; reading them allocates nothing.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/fixed.h"

namespace candela {

struct NoiseTableInfo {
  uint32_t version = 1;
  uint32_t length = 0;
  int32_t beta_milli = 0;
  bool gust = false;
  uint64_t seed = 0;
};

class NoiseTable {
 public:
  static constexpr uint32_t kVersion = 1;
  static constexpr const char* kKind = "noise-table";
  static constexpr uint32_t kMinLength = 16;
  static constexpr uint32_t kMaxLength = 65536;

  NoiseTable() = default;
  // Validates everything; throws ConfigError(source, field, what was expected)
  // (model::ModelError for the container's framing and checksum).
  static NoiseTable parse(std::string_view bytes, const std::string& source);
  static NoiseTable load(const std::string& path);
  // The file's bytes for a table (length must be valid).
  static std::string serialize(const NoiseTableInfo& info, std::span<const uint16_t> samples);

  const NoiseTableInfo& info() const { return info_; }
  uint32_t length() const { return info_.length; }
  bool empty() const { return samples_.empty(); }
  std::span<const uint16_t> samples() const { return samples_; }

  // Sample i (wrapping) as a Fixed in [0, 1).
  Fixed at_index(uint32_t i) const { return Fixed::from_raw(samples_[i & mask_]); }
  // Linear interpolation at a position in samples, Q16.16, wrapping: the
  // table repeats seamlessly because the synthesis is periodic.
  Fixed at(uint32_t position_q16) const {
    const uint32_t i = (position_q16 >> 16) & mask_;
    const int32_t a = samples_[i];
    const int32_t b = samples_[(i + 1) & mask_];
    const int32_t frac = static_cast<int32_t>(position_q16 & 0xFFFFu);
    return Fixed::from_raw(a + static_cast<int32_t>((static_cast<int64_t>(b - a) * frac) >> 16));
  }
  // One trip round the table in Q16.16 samples (wraps uint32 for 65536).
  uint32_t period_q16() const { return info_.length << 16; }

 private:
  NoiseTableInfo info_;
  uint32_t mask_ = 0;
  std::vector<uint16_t> samples_;
};

}  // namespace candela
