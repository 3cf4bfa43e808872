#include "model/noise_table.h"

#include <cstring>
#include <nlohmann/json.hpp>
#include <vector>

#include "core/error.h"
#include "core/file_read.h"
#include "model/model_file.h"
#include "model/model_writer.h"

namespace candela {
namespace {

bool is_pow2(uint32_t n) { return n && !(n & (n - 1)); }

}  // namespace

std::string NoiseTable::serialize(const NoiseTableInfo& info, std::span<const uint16_t> samples) {
  model::ModelWriter w;
  w.set_info({{"kind", kKind},
              {"version", kVersion},
              {"beta_milli", info.beta_milli},
              {"gust", info.gust},
              {"seed", info.seed}});
  std::vector<uint8_t> bytes(2 * samples.size());
  for (size_t i = 0; i < samples.size(); ++i) {
    bytes[2 * i] = static_cast<uint8_t>(samples[i] & 0xFF);
    bytes[2 * i + 1] = static_cast<uint8_t>(samples[i] >> 8);
  }
  w.add("samples", model::DType::kU16, {static_cast<int64_t>(samples.size())}, bytes);
  const std::vector<uint8_t> out = w.bytes();
  return std::string(reinterpret_cast<const char*>(out.data()), out.size());
}

NoiseTable NoiseTable::parse(std::string_view b, const std::string& source) {
  const model::ModelFile f = model::ModelFile::from_bytes(
      std::vector<uint8_t>(reinterpret_cast<const uint8_t*>(b.data()),
                           reinterpret_cast<const uint8_t*>(b.data()) + b.size()),
      source);
  auto fail = [&](const char* field, const std::string& expected) {
    throw ConfigError(source, field, expected);
  };
  const nlohmann::json& info = f.info();
  auto kind = info.find("kind");
  if (kind == info.end() || !kind->is_string() || kind->get<std::string>() != kKind)
    fail("model.kind", "expected \"noise-table\" (a candela-tool noise table)");
  NoiseTable t;
  auto version = info.find("version");
  if (version == info.end() || !version->is_number_unsigned() ||
      version->get<uint64_t>() != kVersion)
    fail("model.version", "expected " + std::to_string(kVersion) + ", got " +
                              (version == info.end() ? std::string("none") : version->dump()) +
                              " (made by a different candela-tool?)");
  t.info_.version = kVersion;
  auto beta = info.find("beta_milli");
  if (beta == info.end() || !beta->is_number_integer() || beta->get<int64_t>() < 0 ||
      beta->get<int64_t>() > 10000)
    fail("model.beta_milli", "expected beta * 1000 in [0, 10000], got " +
                                 (beta == info.end() ? std::string("none") : beta->dump()));
  t.info_.beta_milli = static_cast<int32_t>(beta->get<int64_t>());
  auto gust = info.find("gust");
  if (gust == info.end() || !gust->is_boolean()) fail("model.gust", "expected true or false");
  t.info_.gust = gust->get<bool>();
  auto seed = info.find("seed");
  if (seed == info.end() || !seed->is_number_unsigned())
    fail("model.seed", "expected a non-negative integer");
  t.info_.seed = seed->get<uint64_t>();
  if (info.size() != 5)
    fail("model", "expected only kind, version, beta_milli, gust and seed, got " + info.dump());
  if (f.tensors().size() != 1)
    fail("tensors", "expected one tensor, \"samples\", got " + std::to_string(f.tensors().size()));
  const model::Tensor& s = f.require("samples", model::DType::kU16, {-1});
  const uint64_t n = static_cast<uint64_t>(s.shape[0]);
  if (n > kMaxLength || !is_pow2(static_cast<uint32_t>(n)) || n < kMinLength)
    fail("length", "expected a power of two in [16, 65536] samples, got " + std::to_string(n));
  t.info_.length = static_cast<uint32_t>(n);
  t.samples_.resize(t.info_.length);
  for (uint32_t i = 0; i < t.info_.length; ++i)
    t.samples_[i] = static_cast<uint16_t>(s.data[2 * i] | (s.data[2 * i + 1] << 8));
  t.mask_ = t.info_.length - 1;
  return t;
}

NoiseTable NoiseTable::load(const std::string& path) {
  return parse(read_bounded_file(path, FileKind::kNoiseTable), path);
}

}  // namespace candela
