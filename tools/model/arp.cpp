#include "arp.h"

#include <cmath>
#include <numbers>

namespace candela::tools {

namespace {

Eigen::VectorXd gaussian(int n, std::mt19937_64& rng) {
  std::normal_distribution<double> g(0.0, 1.0);
  Eigen::VectorXd v(n);
  for (int i = 0; i < n; ++i) v[i] = g(rng);
  return v;
}

// Expected statistics gathered by the E-step for the M-step regression
// x_t ~ Theta phi_t, phi_t = [x_{t-1}; ...; x_{t-K}; 1].
struct Stats {
  Eigen::MatrixXd xx, xp, pp;  // sum x x^T, sum x phi^T, sum phi phi^T
  double n = 0;
};

// Initial ARP: per dimension an AR(K) fitted by least squares (diagonal A_k),
// d = 0, B = diag(std) (1 after scaling).
Arp initial_arp(const std::vector<Eigen::MatrixXd>& seqs, int K, int D) {
  Arp a;
  a.order = K;
  a.A.assign(K, Eigen::MatrixXd::Zero(D, D));
  a.d = Eigen::VectorXd::Zero(D);
  a.B = Eigen::MatrixXd::Identity(D, D);
  for (int i = 0; i < D; ++i) {
    Eigen::MatrixXd g = Eigen::MatrixXd::Zero(K, K);
    Eigen::VectorXd r = Eigen::VectorXd::Zero(K);
    for (const auto& s : seqs)
      for (Eigen::Index t = K; t < s.rows(); ++t) {
        Eigen::VectorXd phi(K);
        for (int k = 0; k < K; ++k) phi[k] = s(t - 1 - k, i);
        g += phi * phi.transpose();
        r += phi * s(t, i);
      }
    Eigen::VectorXd c = (g + 1e-6 * Eigen::MatrixXd::Identity(K, K)).ldlt().solve(r);
    for (int k = 0; k < K; ++k) a.A[k](i, i) = c[k];
  }
  return a;
}

// One E-step: a particle filter with the optimal (observation-aware) proposal
// for linear-Gaussian steps, then the statistics of the surviving ancestral
// paths (smoothing by genealogy). Returns the log-likelihood estimate.
double e_step(const Arp& a, const std::vector<Eigen::MatrixXd>& seqs, double r2, int nc,
              std::mt19937_64& rng, Stats& st) {
  const int D = a.dim(), K = a.order, P = K * D + 1;
  st.xx = Eigen::MatrixXd::Zero(D, D);
  st.xp = Eigen::MatrixXd::Zero(D, P);
  st.pp = Eigen::MatrixXd::Zero(P, P);
  st.n = 0;
  const Eigen::MatrixXd Q = a.B * a.B.transpose() + 1e-9 * Eigen::MatrixXd::Identity(D, D);
  // Proposal: x | prediction m, observation z ~ N(S (Q^-1 m + z / r2), S), S = (Q^-1 + I/r2)^-1.
  const Eigen::MatrixXd Qi = Q.ldlt().solve(Eigen::MatrixXd::Identity(D, D));
  const Eigen::MatrixXd S =
      (Qi + Eigen::MatrixXd::Identity(D, D) / r2).ldlt().solve(Eigen::MatrixXd::Identity(D, D));
  const Eigen::MatrixXd Sl = Eigen::LLT<Eigen::MatrixXd>(S).matrixL();
  const Eigen::MatrixXd SQi = S * Qi;
  // Predictive density of z: N(m, Q + r2 I).
  Eigen::LLT<Eigen::MatrixXd> pred(Q + r2 * Eigen::MatrixXd::Identity(D, D));
  const double log_det = 2.0 * pred.matrixL().toDenseMatrix().diagonal().array().log().sum();
  const double log_norm = -0.5 * (D * std::log(2 * std::numbers::pi) + log_det);
  double loglik = 0;
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  for (const auto& z : seqs) {
    const int T = static_cast<int>(z.rows());
    // particles[t] is D x nc; parent[t][i] is the index at t-1 of particle i at t.
    std::vector<Eigen::MatrixXd> particles(T, Eigen::MatrixXd(D, nc));
    std::vector<std::vector<int>> parent(T, std::vector<int>(nc));
    // The first K states: the observations plus observation noise.
    for (int t = 0; t < K; ++t)
      for (int i = 0; i < nc; ++i) {
        particles[t].col(i) = z.row(t).transpose() + std::sqrt(r2) * gaussian(D, rng);
        parent[t][i] = i;
      }
    std::vector<double> logw(nc), w(nc), cum(nc);
    std::vector<int> idx(nc);
    for (int t = K; t < T; ++t) {
      const Eigen::VectorXd zt = z.row(t).transpose();
      for (int i = 0; i < nc; ++i) {
        Eigen::VectorXd m = a.d;
        int p = i;
        for (int k = 0; k < K; ++k) {
          // Walk back the ancestry for x_{t-1-k} of this particle.
          m += a.A[k] * particles[t - 1 - k].col(p);
          p = parent[t - 1 - k][p];
        }
        const Eigen::VectorXd innov = zt - m;
        logw[i] = log_norm - 0.5 * pred.solve(innov).dot(innov);
        particles[t].col(i) = SQi * m + S * zt / r2 + Sl * gaussian(D, rng);
        parent[t][i] = i;
      }
      // Resample (systematic) and log-likelihood increment.
      const double mx = *std::max_element(logw.begin(), logw.end());
      double sum = 0;
      for (int i = 0; i < nc; ++i) sum += w[i] = std::exp(logw[i] - mx);
      loglik += mx + std::log(sum / nc);
      double acc = 0;
      for (int i = 0; i < nc; ++i) cum[i] = (acc += w[i] / sum);
      const double u0 = uni(rng) / nc;
      int j = 0;
      for (int i = 0; i < nc; ++i) {
        const double u = u0 + static_cast<double>(i) / nc;
        while (j < nc - 1 && cum[j] < u) ++j;
        idx[i] = j;
      }
      // Resampling moves whole ancestral lines: copy the chosen particles' state at t
      // and point their parents at the chosen ones' parents.
      Eigen::MatrixXd xt = particles[t];
      std::vector<int> pt = parent[t];
      for (int i = 0; i < nc; ++i) {
        particles[t].col(i) = xt.col(idx[i]);
        parent[t][i] = pt[idx[i]];
      }
    }
    // Statistics over the ancestral paths of the final particles.
    Eigen::MatrixXd path(D, T);
    Eigen::VectorXd phi(P);
    for (int i = 0; i < nc; ++i) {
      int p = i;
      for (int t = T - 1; t >= 0; --t) {
        path.col(t) = particles[t].col(p);
        p = parent[t][p];
      }
      for (int t = K; t < T; ++t) {
        for (int k = 0; k < K; ++k) phi.segment(k * D, D) = path.col(t - 1 - k);
        phi[P - 1] = 1.0;
        st.xx += path.col(t) * path.col(t).transpose();
        st.xp += path.col(t) * phi.transpose();
        st.pp += phi * phi.transpose();
      }
    }
    st.n += static_cast<double>(nc) * (T - K);
  }
  st.xx /= nc;
  st.xp /= nc;
  st.pp /= nc;
  st.n /= nc;
  return loglik;
}

// M-step: maximum-likelihood A_k, d and B from the expected statistics.
Arp m_step(const Stats& st, int K, int D) {
  const int P = K * D + 1;
  Eigen::MatrixXd pp = st.pp + 1e-8 * Eigen::MatrixXd::Identity(P, P);
  Eigen::MatrixXd theta = pp.ldlt().solve(st.xp.transpose()).transpose();  // D x P
  Eigen::MatrixXd C = (st.xx - theta * st.xp.transpose()) / st.n;
  C = 0.5 * (C + C.transpose()) + 1e-9 * Eigen::MatrixXd::Identity(D, D);
  Arp a;
  a.order = K;
  for (int k = 0; k < K; ++k) a.A.push_back(theta.middleCols(k * D, D));
  a.d = theta.col(P - 1);
  Eigen::LLT<Eigen::MatrixXd> llt(C);
  a.B = llt.info() == Eigen::Success
            ? Eigen::MatrixXd(llt.matrixL())
            : Eigen::MatrixXd(C.diagonal().cwiseMax(1e-12).cwiseSqrt().asDiagonal());
  return a;
}

}  // namespace

ArpLearnResult learn_arp(const std::vector<Eigen::MatrixXd>& sequences,
                         const ArpLearnOptions& opt) {
  if (sequences.empty()) throw std::invalid_argument("ARP learning needs at least one sequence");
  const int D = static_cast<int>(sequences[0].cols()), K = opt.order;
  // Scale every parameter to unit standard deviation (and zero mean) for stability.
  Eigen::VectorXd mean = Eigen::VectorXd::Zero(D), sq = Eigen::VectorXd::Zero(D);
  double n = 0;
  for (const auto& s : sequences) {
    if (s.rows() < K + 2 || s.cols() != D)
      throw std::invalid_argument(
          "ARP sequences must be longer than the order and share a dimension");
    mean += s.colwise().sum().transpose();
    sq += s.colwise().squaredNorm().transpose();
    n += static_cast<double>(s.rows());
  }
  mean /= n;
  Eigen::VectorXd sd = (sq / n - mean.cwiseProduct(mean)).cwiseMax(1e-12).cwiseSqrt();
  std::vector<Eigen::MatrixXd> z;
  for (const auto& s : sequences)
    z.push_back((s.rowwise() - mean.transpose()).array().rowwise() / sd.transpose().array());
  std::mt19937_64 rng(opt.seed);
  Arp a = initial_arp(z, K, D);
  ArpLearnResult res;
  Arp best = a;
  double best_ll = -std::numeric_limits<double>::infinity();
  int since_best = 0;
  const double r2 = opt.observation_noise * opt.observation_noise;
  for (int it = 0; it < opt.max_iterations && since_best < opt.patience; ++it) {
    Stats st;
    const double ll = e_step(a, z, r2, opt.particles, rng, st);
    res.log_likelihood.push_back(ll);
    if (ll > best_ll) {
      best_ll = ll;
      best = a;
      since_best = 0;
    } else {
      ++since_best;
    }
    if (opt.progress)
      opt.progress("ARP EM iteration " + std::to_string(it + 1) + ": log-likelihood " +
                   std::to_string(ll));
    a = m_step(st, K, D);
    res.iterations = it + 1;
  }
  // Back to the data's units: x = mean + sd .* s  =>  A_k' = S A_k S^-1,
  // d' = S d + (I - sum A_k') mean, B' = S B.
  const Eigen::MatrixXd S = sd.asDiagonal(), Si = sd.cwiseInverse().asDiagonal();
  Arp out;
  out.order = K;
  Eigen::MatrixXd sumA = Eigen::MatrixXd::Zero(D, D);
  for (int k = 0; k < K; ++k) {
    out.A.push_back(S * best.A[k] * Si);
    sumA += out.A.back();
  }
  out.d = S * best.d + (Eigen::MatrixXd::Identity(D, D) - sumA) * mean;
  out.B = S * best.B;
  res.arp = out;
  return res;
}

Eigen::MatrixXd sample_arp(const Arp& arp, const Eigen::MatrixXd& history, int steps,
                           std::mt19937_64& rng) {
  const int K = arp.order, D = arp.dim();
  Eigen::MatrixXd x(K + steps, D);
  x.topRows(K) = history.bottomRows(K);
  for (int t = K; t < K + steps; ++t) {
    Eigen::VectorXd v = arp.d + arp.B * gaussian(D, rng);
    for (int k = 0; k < K; ++k) v += arp.A[k] * x.row(t - 1 - k).transpose();
    x.row(t) = v.transpose();
  }
  return x.bottomRows(steps);
}

std::vector<double> power_spectrum(const std::vector<double>& x, int segment) {
  std::vector<double> p(segment / 2 + 1, 0.0);
  const int n = static_cast<int>(x.size());
  int count = 0;
  for (int s0 = 0; s0 + segment <= n; s0 += segment / 2, ++count) {
    double mean = 0;
    for (int i = 0; i < segment; ++i) mean += x[s0 + i];
    mean /= segment;
    for (int f = 0; f <= segment / 2; ++f) {
      double re = 0, im = 0;
      for (int i = 0; i < segment; ++i) {
        const double w = 0.5 - 0.5 * std::cos(2 * std::numbers::pi * i / (segment - 1));
        const double v = w * (x[s0 + i] - mean);
        re += v * std::cos(2 * std::numbers::pi * f * i / segment);
        im -= v * std::sin(2 * std::numbers::pi * f * i / segment);
      }
      p[f] += re * re + im * im;
    }
  }
  for (double& v : p) v /= std::max(1, count);
  return p;
}

double log_spectral_distance(const std::vector<double>& a, const std::vector<double>& b) {
  double s = 0;
  int n = 0;
  for (size_t f = 1; f + 1 < std::min(a.size(), b.size()); ++f) {
    const double d = 10.0 * std::log10((a[f] + 1e-12) / (b[f] + 1e-12));
    s += d * d;
    ++n;
  }
  return std::sqrt(s / std::max(1, n));
}

}  // namespace candela::tools
