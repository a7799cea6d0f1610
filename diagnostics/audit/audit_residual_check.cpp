#include "diagnostics/audit/audit_residual_check.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/error.hpp"
#include "core/linalg.hpp"

namespace ambid::diag {
namespace {

constexpr Eigen::Index kMinWindows = 16;
constexpr Eigen::Index kMinReplicasForSpread = 3;  // null replicas that measure the law's spread

// P(T > t) for Student's t with `dof` >= 1 degrees of freedom: A(t | dof) = P(|T| <= t) in
// closed form (Abramowitz & Stegun 26.7.3-4, theta = atan(t / sqrt(dof))).
double student_t_upper_tail(double t, int dof) {
  if (t < 0.0) return 1.0 - student_t_upper_tail(-t, dof);
  const double theta = std::atan(t / std::sqrt(double(dof))), c2 = std::cos(theta) * std::cos(theta);
  double series = 0.0, term = 1.0;
  if (dof % 2 == 0) {
    for (int k = 2; k <= dof; k += 2) {  // 1 + (1/2) c^2 + (1 3)/(2 4) c^4 + ... up to c^(dof-2)
      series += term;
      term *= c2 * double(k - 1) / double(k);
    }
    return 0.5 * (1.0 - std::sin(theta) * series);
  }
  for (int k = 3; k <= dof; k += 2) {  // cos + (2/3) cos^3 + ... up to cos^(dof-2)
    series += term;
    term *= c2 * double(k - 1) / double(k);
  }
  const double inside = 2.0 / std::numbers::pi * (theta + std::sin(theta) * std::cos(theta) * series);
  return 0.5 * (1.0 - inside);
}

double upper_tail_probability(double z) { return 0.5 * std::erfc(z / std::sqrt(2.0)); }

// The z of a scaled chi-square g chi2(nu) with mean `mean` and variance `variance` at t
// (Wilson-Hilferty).
double scaled_chi_square_z(double t, double mean, double variance) {
  const double g = variance / (2.0 * mean), nu = 2.0 * mean * mean / variance;
  const double v = 2.0 / (9.0 * nu);
  return (std::cbrt(std::max(t, 0.0) / (g * nu)) - (1.0 - v)) / std::sqrt(v);
}

}  // namespace

ResidualCheck residual_check(const Eigen::MatrixXd& residual, const Eigen::MatrixXd& excitation, double alpha,
                             const std::vector<bool>& left_out, const std::vector<NullReplica>& null_replicas) {
  if (!(alpha > 0.0 && alpha < 1.0))
    throw Error("audit: residual check probability must be in (0, 1), got " + std::to_string(alpha));
  if (residual.rows() != excitation.rows() || excitation.cols() < 1)
    throw Error("audit: residual check needs the excitation over the same samples as the residual");
  const Eigen::Index N = residual.rows(), q = residual.cols(), p = excitation.cols();
  for (const NullReplica& replica : null_replicas)
    if (replica.residual.rows() != N || replica.residual.cols() != q || replica.excitation.rows() != N ||
        replica.excitation.cols() != p)
      throw Error("audit: residual check null replica of " + std::to_string(replica.residual.rows()) + "x" +
                  std::to_string(replica.residual.cols()) + " residual and " +
                  std::to_string(replica.excitation.rows()) + "x" + std::to_string(replica.excitation.cols()) +
                  " excitation for " + std::to_string(N) + "x" + std::to_string(q) + " and " + std::to_string(p));
  if (!left_out.empty() && std::ssize(left_out) != N)
    throw Error("audit: residual check mask of " + std::to_string(left_out.size()) + " entries for " +
                std::to_string(N) + " samples");
  ResidualCheck c;
  c.coherence_mean = c.coherence_z = Eigen::VectorXd::Zero(q);
  c.coherence_p = Eigen::VectorXd::Ones(q);
  Eigen::Index L = 0;
  for (Eigen::Index candidate : {256, 128, 64})
    if (N / candidate >= (candidate == 256 ? 24 : kMinWindows)) {
      L = candidate;
      break;
    }
  if (L == 0 || N / L <= p) {
    c.reason = std::to_string(N) + " samples hold fewer than " + std::to_string(kMinWindows) + " windows of 64";
    return c;
  }
  // Windows holding a sample where a controller clamp acted are left out.
  std::vector<Eigen::Index> starts;
  for (Eigen::Index m = 0; m < N / L; ++m)
    if (left_out.empty() ||
        std::find(left_out.begin() + m * L, left_out.begin() + (m + 1) * L, true) == left_out.begin() + (m + 1) * L)
      starts.push_back(m * L);
  const Eigen::Index K = std::ssize(starts), bins = L / 2;  // bins 1 .. L/2 - 1 are used
  if (K < kMinWindows || K <= p) {
    c.reason = std::to_string(N / L - K) + " of the " + std::to_string(N / L) + " windows of " + std::to_string(L) +
               " hold a sample where a controller clamp acted; fewer than " + std::to_string(kMinWindows) + " remain";
    return c;
  }
  c.determinable = true;
  c.window = L;
  c.windows = K;

  // DFT of every Hann-windowed, mean-free window: spectra[m] is bins x (q + p).
  Eigen::MatrixXcd twiddle(bins, L);
  for (Eigen::Index b = 0; b < bins; ++b)
    for (Eigen::Index k = 0; k < L; ++k)
      twiddle(b, k) = std::polar(1.0, -2.0 * std::numbers::pi * double(b * k % L) / double(L));
  Eigen::VectorXd hann(L);
  for (Eigen::Index k = 0; k < L; ++k) hann[k] = 0.5 - 0.5 * std::cos(2.0 * std::numbers::pi * double(k) / double(L));
  const auto spectra_of = [&](const Eigen::MatrixXd& e, const Eigen::MatrixXd& x) {
    std::vector<Eigen::MatrixXcd> out;
    for (const Eigen::Index start : starts) {
      Eigen::MatrixXd block(L, q + p);
      block << e.middleRows(start, L), x.middleRows(start, L);
      block.rowwise() -= block.colwise().mean();
      out.push_back(twiddle * (hann.asDiagonal() * block).cast<std::complex<double>>());
    }
    return out;
  };
  const std::vector<Eigen::MatrixXcd> spectra = spectra_of(residual, excitation);
  // Sum over the windows of conj(e_j) r in bin b (p entries): the cross-spectrum the check weighs.
  const auto cross = [&](const std::vector<Eigen::MatrixXcd>& s, Eigen::Index b, Eigen::Index j) {
    Eigen::VectorXcd sum = Eigen::VectorXcd::Zero(p);
    for (const auto& w : s) sum += w.block(b, q, 1, p).transpose() * std::conj(w(b, j));
    return sum;
  };
  std::vector<std::vector<Eigen::MatrixXcd>> replica_spectra;
  for (const NullReplica& replica : null_replicas)
    replica_spectra.push_back(spectra_of(replica.residual, replica.excitation));
  c.null_replicas = int(null_replicas.size());
  // The replicas' mean is itself an estimate: its scatter adds 1/M of the record's.
  const double inflation = null_replicas.empty() ? 1.0 : 1.0 + 1.0 / double(null_replicas.size());

  // Excited bins: every other bin where the excitations' power is >= 1 % of its maximum.
  Eigen::VectorXd r_power = Eigen::VectorXd::Zero(bins);
  for (const auto& s : spectra) r_power += s.rightCols(p).cwiseAbs2().rowwise().sum();
  std::vector<Eigen::Index> excited;
  for (Eigen::Index b = 2; b < bins; b += 2)
    if (r_power[b] >= 0.01 * r_power.segment(1, bins - 1).maxCoeff()) excited.push_back(b);
  const double Kd = double(K);

  // Per excited bin: the excitations' cross-spectrum, its rank (a multisine can give both
  // excitations the same line in a bin: rank 1) and pseudo-inverse.
  struct Bin {
    Eigen::Index b;
    Eigen::MatrixXcd Srr_pinv;
    double rank;
  };
  const auto bins_of = [&](const std::vector<Eigen::MatrixXcd>& s) {
    std::vector<Bin> out;
    for (Eigen::Index b : excited) {
      Eigen::MatrixXcd Srr = Eigen::MatrixXcd::Zero(p, p);
      for (const auto& w : s) {
        const Eigen::VectorXcd rb = w.block(b, q, 1, p).transpose();
        Srr += rb * rb.adjoint();
      }
      const linalg::HermitianEigen eig = linalg::hermitian_eigen(Srr);
      const double largest = eig.values.maxCoeff();
      Eigen::MatrixXcd pinv = Eigen::MatrixXcd::Zero(p, p);
      double rank = 0.0;
      for (Eigen::Index k = 0; k < p; ++k)
        if (eig.values[k] > 1e-6 * largest) {
          pinv += eig.vectors.col(k) * eig.vectors.col(k).adjoint() / eig.values[k];
          rank += 1.0;
        }
      if (rank > 0.0 && rank < Kd) out.push_back({b, pinv, rank});
    }
    return out;
  };
  // T of output j of the windows' spectra `s` (its bins `of_bins`), the mean cross-spectrum of
  // `nulls` subtracted.
  using Spectra = std::vector<Eigen::MatrixXcd>;
  const auto statistic = [&](const Spectra& s, const std::vector<Bin>& of_bins,
                             const std::vector<const Spectra*>& nulls, Eigen::Index j) {
    double sum = 0.0;
    for (const Bin& bin : of_bins) {
      Eigen::VectorXcd Sre = cross(s, bin.b, j);
      double See = 0.0;
      for (const auto& w : s) See += std::norm(w(bin.b, j));
      if (!(See > 0.0)) continue;
      if (!nulls.empty()) {
        Eigen::VectorXcd expected = Eigen::VectorXcd::Zero(p);
        for (const Spectra* n : nulls) expected += cross(*n, bin.b, j);
        Sre -= expected / double(nulls.size());
      }
      // Sre^H Srr^+ Sre / See ~ Beta(rank, K - rank) under noise independent of r.
      sum += std::clamp(Sre.dot(bin.Srr_pinv * Sre).real() / See, 0.0, 1.0);
    }
    return sum;
  };
  const std::vector<Bin> used = bins_of(spectra);
  c.bins = Eigen::Index(used.size());
  std::vector<const Spectra*> all_nulls;
  std::vector<std::vector<Bin>> replica_bins;
  for (const Spectra& s : replica_spectra) {
    all_nulls.push_back(&s);
    replica_bins.push_back(bins_of(s));
  }
  const auto M = std::ssize(replica_spectra);
  for (Eigen::Index j = 0; j < q; ++j) {
    double mean = 0.0, variance = 0.0;
    for (const Bin& bin : used) {
      double See = 0.0;
      for (const auto& s : spectra) See += std::norm(s(bin.b, j));
      if (!(See > 0.0)) continue;
      mean += inflation * bin.rank / Kd;
      variance += inflation * inflation * bin.rank * (Kd - bin.rank) / (Kd * Kd * (Kd + 1.0));
    }
    if (!(mean > 0.0)) continue;
    const double sum = statistic(spectra, used, all_nulls, j);
    c.coherence_mean[j] = sum / double(used.size());
    c.coherence_z[j] = scaled_chi_square_z(sum, mean, variance);
    c.coherence_p[j] = upper_tail_probability(c.coherence_z[j]);
    if (M < kMinReplicasForSpread) continue;
    // The replicas' own spread: each checked against the others' mean.
    Eigen::VectorXd left_one_out(M);
    for (Eigen::Index m = 0; m < M; ++m) {
      std::vector<const Spectra*> others;
      for (Eigen::Index n = 0; n < M; ++n)
        if (n != m) others.push_back(all_nulls[std::size_t(n)]);
      left_one_out[m] = statistic(replica_spectra[std::size_t(m)], replica_bins[std::size_t(m)], others, j);
    }
    const double spread = std::sqrt((left_one_out.array() - left_one_out.mean()).square().sum() / double(M - 1));
    if (!(spread > 0.0)) continue;
    const double z = (sum - left_one_out.mean()) / spread, p_spread = student_t_upper_tail(z, int(M - 1));
    if (p_spread > c.coherence_p[j]) {
      c.coherence_z[j] = z;
      c.coherence_p[j] = p_spread;
    }
  }
  c.p_value = std::min(1.0, c.coherence_p.minCoeff() * double(q));
  c.consistent = c.p_value >= alpha;
  return c;
}

}  // namespace ambid::diag
