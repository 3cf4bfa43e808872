// Noise tables: the synthesis (tools/noise) and the runtime reader
// (model/noise_table): spectra, wrap, gust shape, determinism, validation.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/error.h"
#include "embedded_noise_tables.h"
#include "model/model_writer.h"
#include "model/noise_table.h"
#include "noise/noise_synth.h"

namespace candela {
namespace {

class SpectralSlope : public ::testing::TestWithParam<double> {};

TEST_P(SpectralSlope, QuantisedTableHasSlopeMinusBeta) {
  const double beta = GetParam();
  for (uint64_t seed : {1u, 2u, 99u}) {
    const NoiseTable t = noise::make_table(beta, 4096, seed, false);
    const auto fit = noise::fit_spectral_slope(noise::to_unit(t));
    EXPECT_NEAR(fit.slope, -beta, 0.1) << "seed " << seed;
  }
}
INSTANTIATE_TEST_SUITE_P(Betas, SpectralSlope, ::testing::Values(0.0, 1.0, 2.0, 2.8));

TEST(NoiseTable, WrapsContinuously) {
  // The step from the last sample back to the first is an ordinary step:
  // within a few typical steps, for smooth and rough noise alike.
  for (double beta : {1.0, 2.0, 2.8}) {
    const NoiseTable t = noise::make_table(beta, 4096, 7, false);
    const auto s = noise::table_stats(noise::to_unit(t));
    EXPECT_LT(s.wrap_step, 4 * s.mean_step + 2.0 / 65536) << "beta " << beta;
    // And the reader's interpolation crosses the seam between those two samples.
    const uint32_t seam = (t.length() - 1) << 16;
    const Fixed mid = t.at(seam + 0x8000);
    const Fixed a = t.at_index(t.length() - 1), b = t.at_index(0);
    EXPECT_LE(mid, std::max(a, b));
    EXPECT_GE(mid, std::min(a, b));
    EXPECT_EQ(t.at(t.period_q16()), t.at(0));
  }
}

TEST(NoiseTable, GustTableStartsAtItsMinimumAndEndsNearIt) {
  for (uint64_t seed : {3u, 4u, 5u}) {
    const NoiseTable t = noise::make_table(2.4, 4096, seed, true);
    const auto v = noise::to_unit(t);
    const auto s = noise::table_stats(v);
    EXPECT_EQ(s.argmin, 0u);
    EXPECT_EQ(t.samples()[0], 0);
    // Periodic, so the last sample is one ordinary step from the minimum.
    EXPECT_LT(v.back(), 0.05);
    EXPECT_GT(s.max, 0.99);
  }
}

TEST(NoiseTable, SameSeedSameBytesOtherSeedOtherBytes) {
  auto bytes = [](uint64_t seed) {
    const NoiseTable t = noise::make_table(2.0, 1024, seed, false);
    return NoiseTable::serialize(t.info(), t.samples());
  };
  EXPECT_EQ(bytes(11), bytes(11));
  EXPECT_NE(bytes(11), bytes(12));
}

TEST(NoiseTable, InterpolatesLinearlyInIntegers) {
  const NoiseTable t = noise::make_table(1.0, 64, 5, false);
  for (uint32_t i = 0; i < 64; ++i) {
    const int32_t a = t.samples()[i], b = t.samples()[(i + 1) % 64];
    EXPECT_EQ(t.at(i << 16).raw, a);
    EXPECT_EQ(t.at((i << 16) + 0x4000).raw, a + ((b - a) * 0x4000 >> 16));
  }
}

TEST(NoiseTable, RejectsBrokenFilesNamingTheField) {
  const NoiseTable t = noise::make_table(2.0, 64, 5, false);
  const std::string good = NoiseTable::serialize(t.info(), t.samples());
  auto field_of = [](const std::string& bytes) -> std::string {
    try {
      NoiseTable::parse(bytes, "x.cnoise");
    } catch (const ConfigError& e) {
      EXPECT_EQ(e.file(), "x.cnoise");
      return e.key();
    }
    return "accepted";
  };
  EXPECT_EQ(field_of(good), "accepted");
  // The table is a container file (model/model_file.h): framing, header and
  // checksum faults are the container reader's, named as for a model.
  EXPECT_EQ(field_of(good.substr(0, 5)), "header length");
  EXPECT_EQ(field_of(good.substr(0, 100)), "header");
  EXPECT_EQ(field_of(good + "xx"), "data");
  std::string b = good;
  b[good.size() - 10] ^= 1;
  EXPECT_EQ(field_of(b), "__metadata__.checksum");
  // What only a noise table checks, in a well-formed container.
  auto remade = [&](nlohmann::json info, std::vector<uint16_t> samples) {
    model::ModelWriter w;
    w.set_info(std::move(info));
    w.add("samples", model::DType::kU16, {static_cast<int64_t>(samples.size())},
          {reinterpret_cast<const uint8_t*>(samples.data()), 2 * samples.size()});
    const auto out = w.bytes();
    return std::string(out.begin(), out.end());
  };
  const nlohmann::json info = {
      {"kind", "noise-table"}, {"version", 1}, {"beta_milli", 2000}, {"gust", false}, {"seed", 5}};
  const std::vector<uint16_t> samples(t.samples().begin(), t.samples().end());
  EXPECT_EQ(field_of(remade(info, samples)), "accepted");
  auto with = [&](const char* key, nlohmann::json v) {
    nlohmann::json i = info;
    i[key] = std::move(v);
    return remade(i, samples);
  };
  EXPECT_EQ(field_of(with("kind", "eigenfires")), "model.kind");
  EXPECT_EQ(field_of(with("version", 2)), "model.version");
  EXPECT_EQ(field_of(with("beta_milli", 20000)), "model.beta_milli");
  EXPECT_EQ(field_of(with("gust", 4)), "model.gust");
  EXPECT_EQ(field_of(with("seed", -1)), "model.seed");
  EXPECT_EQ(field_of(remade(info, std::vector<uint16_t>(65, 0))), "length");
  EXPECT_EQ(field_of(remade(info, std::vector<uint16_t>(8, 0))), "length");
  try {
    NoiseTable::parse(with("kind", "eigenfires"), "x.cnoise");
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_STREQ(e.what(),
                 "x.cnoise: model.kind: expected \"noise-table\" (a candela-tool noise table)");
  }
  try {
    NoiseTable::load("/nonexistent/table.cnoise");
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.file(), "/nonexistent/table.cnoise");
  }
}

TEST(BuiltinNoiseTables, AreMadeAtBuildTimeWithTheirBetas) {
  for (const char* name : {"b10_0", "b14_1", "b20_2", "b24_0", "b28_1"}) {
    const auto bytes = noise_tables::find(std::string(name) + ".cnoise");
    ASSERT_FALSE(bytes.empty()) << name;
    const NoiseTable t = NoiseTable::parse(bytes, name);
    const double beta = t.info().beta_milli / 1000.0;
    EXPECT_NEAR(noise::fit_spectral_slope(noise::to_unit(t)).slope, -beta, 0.1) << name;
  }
  const NoiseTable g = NoiseTable::parse(noise_tables::find("gust_b24.cnoise"), "gust");
  EXPECT_TRUE(g.info().gust);
  EXPECT_EQ(g.samples()[0], 0);
}

}  // namespace
}  // namespace candela
