// The noise command (noise_cli.h): makes 1/f^beta noise tables for the
// candle (and any element that wants wind-like fluctuation), and analyses
// existing ones.
#include "noise/noise_cli.h"

#include <CLI/CLI.hpp>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>

#include "core/atomic_file.h"
#include "core/cli_usage.h"
#include "core/error.h"
#include "noise/noise_synth.h"

namespace candela::noise {
namespace {

// Writes only when the bytes differ, so build-time tables keep their
// timestamps and nothing downstream rebuilds needlessly. Throws FileError.
void write_if_changed(const std::string& path, const std::string& bytes) {
  {
    std::ifstream in(path, std::ios::binary);
    if (in) {
      std::stringstream ss;
      ss << in.rdbuf();
      if (ss.str() == bytes) return;
    }
  }
  write_atomic(path, bytes);
}

int analyze(const std::string& path) {
  const NoiseTable t = NoiseTable::load(path);
  const auto v = noise::to_unit(t);
  const auto fit = noise::fit_spectral_slope(v);
  const auto s = noise::table_stats(v);
  std::printf("file: %s\n", path.c_str());
  std::printf("version: %u\nlength: %u\nbeta (made with): %.3f\ngust: %s\nseed: %llu\n",
              t.info().version, t.length(), t.info().beta_milli / 1000.0,
              t.info().gust ? "yes" : "no", static_cast<unsigned long long>(t.info().seed));
  std::printf("spectral slope: %.4f (expect -beta = %.3f), fit r2 %.4f\n", fit.slope,
              -t.info().beta_milli / 1000.0, fit.r2);
  std::printf("min: %.5f at index %u\nmax: %.5f\nmean: %.5f\nstddev: %.5f\n", s.min, s.argmin,
              s.max, s.mean, s.stddev);
  std::printf("mean |step|: %.6f\nwrap |step|: %.6f\n", s.mean_step, s.wrap_step);
  return 0;
}

}  // namespace

int run_noise_command(int argc, char** argv, const char* program) {
  CLI::App app{
      "Make a 1/f^beta noise table by spectral synthesis (inverse real FFT), "
      "scaled to [0, 1] and stored as Q0.16 integers; or analyse one.",
      program};
  double beta = 2.0;
  uint32_t length = 4096;
  uint64_t seed = 1;
  bool gust = false;
  std::string out, analyze_path;
  app.add_option("--beta", beta, "Spectral exponent: 0 white, 1 pink, 2 brown")
      ->check(CLI::Range(0.0, 10.0));
  app.add_option("--length", length, "Samples, a power of two in [16, 65536]")
      ->check([](const std::string& s) -> std::string {
        unsigned long n = std::strtoul(s.c_str(), nullptr, 10);
        if (n < 16 || n > 65536 || (n & (n - 1)))
          return "expected a power of two in [16, 65536], got " + s;
        return {};
      });
  app.add_option("--seed", seed, "Random seed for the phases");
  app.add_flag("--gust", gust,
               "Rotate the table so its minimum is at index 0 (gusts start and end calm)");
  app.add_option("--out", out, "Where to write the table");
  app.add_option("--analyze", analyze_path, "Print a table's fitted spectral slope and statistics")
      ->check(CLI::ExistingFile);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return candela::usage_exit(app, e);
  }
  if (!analyze_path.empty()) {
    try {
      return analyze(analyze_path);
    } catch (const ConfigError& e) {  // a bad table: say which field, do not abort
      std::fprintf(stderr, "%s: %s\n", program, e.what());
      return 2;
    }
  }
  if (out.empty()) {
    std::fprintf(stderr, "%s: --out FILE is required (or --analyze FILE)\n", program);
    return 2;
  }
  const NoiseTable t = noise::make_table(beta, length, seed, gust);
  try {
    write_if_changed(out, NoiseTable::serialize(t.info(), t.samples()));
  } catch (const FileError& e) {
    std::fprintf(stderr, "%s: %s\n", program, e.what());
    return 1;
  }
  return 0;
}

}  // namespace candela::noise
