// The ARP learned by EM with condensation recovers a known process. Pure
// numerics, 2 s normally and 5 minutes under ASan: it runs in the normal
// build only (label "numeric"); under the sanitizers the same code (learn_arp,
// sample_arp) runs in BreezeFlames.SynthesisedHeightHasTheRealSpectrum.
#include "arp.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

namespace ct = candela::tools;

TEST(Arp, EmWithCondensationRecoversAKnownAr2) {
  // x_t = A1 x_{t-1} + A2 x_{t-2} + d + B w_t in three dimensions, coupled.
  const int D = 3;
  ct::Arp truth;
  truth.order = 2;
  Eigen::MatrixXd A1(D, D), A2(D, D), B(D, D);
  A1 << 1.2, 0.2, 0.0, -0.1, 0.9, 0.1, 0.0, 0.0, 0.5;
  A2 << -0.5, 0.0, 0.0, 0.0, -0.2, 0.0, 0.1, 0.0, 0.2;
  B << 0.5, 0, 0, 0.1, 0.3, 0, 0, 0.05, 0.4;
  truth.A = {A1, A2};
  truth.d = Eigen::Vector3d(1.0, -0.5, 2.0);
  truth.B = B;
  std::mt19937_64 rng(7);
  std::vector<Eigen::MatrixXd> seqs;
  for (int s = 0; s < 3; ++s) {
    Eigen::MatrixXd h = Eigen::MatrixXd::Zero(2, D);
    Eigen::MatrixXd x = ct::sample_arp(truth, h, 900, rng);
    seqs.push_back(x.bottomRows(800));  // past the start-up transient
  }
  ct::ArpLearnOptions o;
  o.particles = 100;
  o.observation_noise = 0.05;
  ct::ArpLearnResult r = ct::learn_arp(seqs, o);
  std::printf("EM iterations %d, log-likelihood %.1f -> %.1f\n", r.iterations,
              r.log_likelihood.front(), r.log_likelihood.back());
  const double a_err =
      std::max((r.arp.A[0] - A1).cwiseAbs().maxCoeff(), (r.arp.A[1] - A2).cwiseAbs().maxCoeff());
  const Eigen::MatrixXd q = r.arp.B * r.arp.B.transpose(), qt = B * B.transpose();
  const double q_err = (q - qt).cwiseAbs().maxCoeff() / qt.cwiseAbs().maxCoeff();
  // d is compared through the process mean it implies, mu = (I - A1 - A2)^-1 d.
  const Eigen::VectorXd mu =
      (Eigen::MatrixXd::Identity(D, D) - r.arp.A[0] - r.arp.A[1]).lu().solve(r.arp.d);
  const Eigen::VectorXd mut = (Eigen::MatrixXd::Identity(D, D) - A1 - A2).lu().solve(truth.d);
  std::printf("max |A - A_true| %.3f, noise covariance error %.1f%%, mean error %.3f\n", a_err,
              100 * q_err, (mu - mut).cwiseAbs().maxCoeff());
  EXPECT_LT(a_err, 0.08);
  EXPECT_LT(q_err, 0.2);
  EXPECT_LT((mu - mut).cwiseAbs().maxCoeff(), 0.1 * mut.cwiseAbs().maxCoeff());
  EXPECT_GE(r.log_likelihood.back(), r.log_likelihood.front()) << "EM should not lose likelihood";
}
