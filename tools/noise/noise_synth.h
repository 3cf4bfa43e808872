// 1/f^beta noise by spectral synthesis (Peitgen & Saupe), the offline half
// of the noise tables: FFTW does the inverse transform; the runtime only
// reads the quantised result (model/noise_table.h).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "model/noise_table.h"

namespace candela::noise {

// One period of 1/f^beta noise: amplitudes C / k^(beta/2) with uniformly
// random phases for 0 < k < N/2, conjugate-symmetric, inverse real FFT.
// length must be even. Same seed, same result.
std::vector<double> synthesize(double beta, uint32_t length, uint64_t seed);

// Scales to [0, 1] and quantises to Q0.16 (0 .. 65535). With gust, the
// table is rotated so that its minimum sits at index 0: played once from the
// start, it begins and (being periodic) ends near calm.
std::vector<uint16_t> quantize(std::span<const double> signal, bool gust);

// Everything above in one call, ready to write.
NoiseTable make_table(double beta, uint32_t length, uint64_t seed, bool gust);

struct SpectrumFit {
  double slope = 0;      // of log power against log frequency: about -beta
  double intercept = 0;  // log10 power at k = 1
  double r2 = 0;         // goodness of the straight-line fit
};
// Least-squares line through the periodogram (k = 1 .. N/2 - 1) in log-log
// coordinates, with points averaged in log-spaced bins so the many high
// frequencies do not outvote the few low ones.
SpectrumFit fit_spectral_slope(std::span<const double> signal);

struct TableStats {
  double min = 0, max = 0, mean = 0, stddev = 0;
  double mean_step = 0;  // mean |x[i+1] - x[i]|
  double wrap_step = 0;  // |x[0] - x[N-1]|: continuous wrap keeps this near mean_step
  uint32_t argmin = 0;
};
TableStats table_stats(std::span<const double> values);

// The table's samples as doubles in [0, 1).
std::vector<double> to_unit(const NoiseTable& table);

}  // namespace candela::noise
