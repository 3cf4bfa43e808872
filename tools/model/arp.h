// Learning Flames dynamics: a K-th order auto-regressive process
//   x_t = sum_k A_k x_{t-k} + d + B w_t,   w_t ~ N(0, I)
// learned by EM whose E-step is a condensation (particle) filter over noisy
// observations z_t = x_t + v_t (Stich & Magnor, after North & Blake).
#pragma once

#include <Eigen/Dense>
#include <functional>
#include <random>
#include <string>
#include <vector>

namespace candela::tools {

struct Arp {
  int order = 2;
  std::vector<Eigen::MatrixXd> A;  // K matrices, D x D
  Eigen::VectorXd d;
  Eigen::MatrixXd B;  // lower triangular, B B^T = process noise covariance
  int dim() const { return static_cast<int>(d.size()); }
};

struct ArpLearnOptions {
  int order = 2;                   // K
  int particles = 200;             // Nc
  double observation_noise = 0.1;  // std of v_t in units of each parameter's std
  int patience = 3;                // stop after this many iterations without a better likelihood
  int max_iterations = 40;
  uint64_t seed = 1;
  std::function<void(const std::string&)> progress;
};

struct ArpLearnResult {
  Arp arp;                             // in the data's own units
  std::vector<double> log_likelihood;  // per EM iteration
  int iterations = 0;
};

// sequences: each T x D (rows are time steps), at least order + 2 rows.
ArpLearnResult learn_arp(const std::vector<Eigen::MatrixXd>& sequences, const ArpLearnOptions& opt);

// Samples `steps` new states after the given history (order rows, oldest first).
Eigen::MatrixXd sample_arp(const Arp& arp, const Eigen::MatrixXd& history, int steps,
                           std::mt19937_64& rng);

// Power spectrum (periodogram averaged over Welch segments of `segment` samples, Hann window).
std::vector<double> power_spectrum(const std::vector<double>& x, int segment);
// Root-mean-square difference of two spectra in dB (bins 1..n/2-1, DC left out).
double log_spectral_distance(const std::vector<double>& a, const std::vector<double>& b);

}  // namespace candela::tools
