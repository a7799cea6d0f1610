#include "identifier/families/maglev_greybox.hpp"

#include <array>
#include <cmath>
#include <sstream>

#include "core/error.hpp"
#include "core/linalg.hpp"
#include "identifier/nonlinear_least_squares.hpp"

namespace ambid::ident {
namespace {

using Index = Eigen::Index;
const std::string kGreyboxWho = "maglev grey-box fit";

// 4-point Gauss-Legendre on [0, 1].
constexpr std::array<double, 4> kNode = {0.5 - 0.5 * 0.8611363115940526, 0.5 - 0.5 * 0.3399810435848563,
                                         0.5 + 0.5 * 0.3399810435848563, 0.5 + 0.5 * 0.8611363115940526};
constexpr std::array<double, 4> kWeight = {0.5 * 0.3478548451374538, 0.5 * 0.6521451548625461, 0.5 * 0.6521451548625461,
                                           0.5 * 0.3478548451374538};

double nominal_value(const MaglevGreyBoxInput& in, const char* name) {
  const auto it = in.nominal.find(name);
  if (it == in.nominal.end()) throw Error(kGreyboxWho + ": nominal parameter '" + name + "' is missing");
  if (!(it->second > 0.0) || !std::isfinite(it->second)) {
    std::ostringstream msg;
    msg << kGreyboxWho << ": nominal parameter '" << name << "' must be positive, got " << it->second;
    throw Error(msg.str());
  }
  return it->second;
}

// i^(n_i - 1) of the back-EMF, with the current floored at 1 % of the operating current: for
// n_i < 1 the family's flux diverges at zero current (the DAC clamped at 0 V empties the coil).
double emf_factor(double current, double n_i, double i0) {
  return std::pow(std::max(std::abs(current), 0.01 * i0), n_i - 1.0);
}

// The positive eigenvalue of the linearisation at the operating point (x0, i0), the force and
// back-EMF constants closed by gravity balance there (maglev_frf_structure.hpp:
// A = [0 1 0; a 0 -b; 0 emf -R/L]), of q = [rho, n_i, n_x, R, L, Ke]. The back-EMF's coupling
// lowers it below sqrt(a): by 1 % at 14 mm on the rig.
double linearised_unstable_pole(const Eigen::VectorXd& q, double g, double x0, double i0) {
  const double rho = q(0), n_i = q(1), n_x = q(2), R = q(3), L = q(4), Ke = q(5);
  const double emf = n_i * Ke / rho * std::pow(i0, n_i - 1.0) / (std::pow(x0, n_x) * L);
  Eigen::Matrix3d A;
  A << 0.0, 1.0, 0.0, n_x * g / x0, 0.0, -n_i * g / i0, 0.0, emf, -R / L;
  return linalg::eigenvalues(A).real().maxCoeff();
}

// The current estimates every step works with (nominal values before the first pass).
struct Estimates {
  double R, L, Ke, kw, n_i, n_x, rho, g;
};

// The coil current and the gap within sample interval j, at s in [0, 1] of it. The current
// follows the coil's step response to the held command (back-EMF from the mean velocity). The
// gap is the chord from x[j] to x[j+1] plus the double integral of the model's acceleration
// with that current, less its own chord: the interpolation knows that the acceleration jumps
// with the command at every sample, which no polynomial through the samples does (a
// Catmull-Rom cubic left n_i and n_x 0.07 % low, the chord alone 0.4 %). The acceleration is
// linearised in the current about its mid-sample value and in the gap about x[j] along the
// chord: the force's gap law is the plant's negative stiffness n_x g / x, whose pull over a
// sample bends the velocity by a fraction ~ n_x g / x Ts^2 / 3 of itself, late in the sample
// where the coil's response weights the back-EMF. Held at x[j] (until 2026-12-03) the
// back-EMF regressor read 0.29 % low at 3.25 ms and 0.50 % low at 4 ms against the simulator's
// own integral of the true motion, and Ke came out that much high on noise-free records.
class SampleMotion {
 public:
  SampleMotion(const MaglevGreyBoxInput& in, Index j, const Estimates& e)
      : Ts_(in.sample_time), x0_(in.x(j)), chord_(in.x(j + 1) - in.x(j)), lambda_(e.R / e.L) {
    const double velocity = chord_ / Ts_;
    const double emf = -e.n_i * e.Ke * emf_factor(in.i(j), e.n_i, in.i0) * velocity / std::pow(x0_, e.n_x);
    settled_ = (e.kw * in.u(j) - emf) / e.R;
    step_ = in.i(j) - settled_;
    const double mid = std::max(current(0.5), 1e-3 * in.i0);
    const double G = e.g * e.rho * std::pow(in.x0 / x0_, e.n_x);
    a1_ = -G * e.n_i * std::pow(mid / in.i0, e.n_i - 1.0) * step_ / in.i0;
    a0_ = e.g - G * std::pow(mid / in.i0, e.n_i) - a1_ * std::exp(-0.5 * lambda_ * Ts_);
    a2_ = G * std::pow(mid / in.i0, e.n_i) * e.n_x * velocity / x0_;  // d/dt of the force's gap law
    end_ = twice_integrated(Ts_);
  }
  double current(double s) const { return settled_ + step_ * std::exp(-lambda_ * Ts_ * s); }
  double gap(double s) const { return x0_ + chord_ * s + twice_integrated(s * Ts_) - s * end_; }
  // dx/ds (the rate per unit s: Ts times dx/dt).
  double rate(double s) const {
    const double t = s * Ts_;
    return chord_ + Ts_ * (a0_ * t + a1_ * (1.0 - std::exp(-lambda_ * t)) / lambda_ + 0.5 * a2_ * t * t) - end_;
  }

 private:
  // The double integral from 0 of a0 + a1 exp(-lambda t) + a2 t.
  double twice_integrated(double t) const {
    return 0.5 * a0_ * t * t + a1_ * (std::exp(-lambda_ * t) - 1.0 + lambda_ * t) / (lambda_ * lambda_) +
           a2_ * t * t * t / 6.0;
  }
  double Ts_, x0_, chord_, lambda_, settled_ = 0, step_ = 0, a0_ = 0, a1_ = 0, a2_ = 0, end_ = 0;
};

struct Coil {
  double a = 0, beta = 0, gamma = 0;
  Eigen::Matrix3d covariance;  // of (a, beta, gamma)
  double residual_rms = 0;
};

// The back-EMF regressor of sample k: i^(n_i-1) times the integral over the sample of
// x'/x^n_x weighted by the coil's response exp(-(R/L)(Ts - t)) (4 Gauss-Legendre nodes on the
// cubic through the logged gaps): the motion late in the sample counts more.
double emf_regressor(const MaglevGreyBoxInput& in, Index k, const Estimates& e) {
  const SampleMotion motion(in, k, e);
  const double decay = e.R / e.L;
  double sum = 0.0;
  for (int q = 0; q < 4; ++q) {
    const double s = kNode[std::size_t(q)];
    sum += kWeight[std::size_t(q)] * std::exp(-decay * in.sample_time * (1.0 - s)) * motion.rate(s) /
           std::pow(motion.gap(s), e.n_x);
  }
  return emf_factor(in.i(k), e.n_i, in.i0) * sum;  // the rate is per unit s: the Ts of dt cancels
}

// The overlap-weighted score covariance of a least-squares fit whose equations k and k + l
// share samples for |l| < lags (Bartlett weights): sum over l of w_l sum_k J_k' r_k r_{k+l} J_{k+l}.
Eigen::MatrixXd score_covariance(const Eigen::MatrixXd& J, const Eigen::VectorXd& r, Index lags) {
  Eigen::MatrixXd S = Eigen::MatrixXd::Zero(J.cols(), J.cols());
  for (Index l = -lags; l <= lags; ++l) {
    const double bartlett = 1.0 - double(std::abs(l)) / double(lags + 1);
    for (Index k = std::max<Index>(0, -l); k < r.size() && k + l < r.size(); ++k)
      S += bartlett * (J.row(k).transpose() * r(k)) * (r(k + l) * J.row(k + l));
  }
  return S;
}

// Per sample j of n, the sum of the rows of the windows (M samples each, every start) that hold
// it: the windowed score sum_k row_k' r_k is sum_j row_of_sample_j' e_j with e the per-sample
// residuals, whose own correlation is short.
Eigen::MatrixXd window_rows_of_samples(const Eigen::MatrixXd& rows, Index n) {
  const Index windows = rows.rows(), M = n - windows + 1;
  Eigen::MatrixXd prefix = Eigen::MatrixXd::Zero(windows + 1, rows.cols());
  for (Index k = 0; k < windows; ++k) prefix.row(k + 1) = prefix.row(k) + rows.row(k);
  Eigen::MatrixXd out(n, rows.cols());
  for (Index j = 0; j < n; ++j)
    out.row(j) = prefix.row(std::min(j, windows - 1) + 1) - prefix.row(std::max<Index>(0, j - M + 1));
  return out;
}

// Step 1: i[k+1] = a i[k] + beta u[k] + gamma phi[k] summed over windows of M samples
// (M = coil_window / Ts, every start k), columns equilibrated before the QR, phi from the
// previous estimates. The sum is the coil equation's own discretisation over the window: the
// back-EMF regressor is the response-weighted change of the law's potential over each sample,
// so its sum telescopes and the logged gap's noise (sensor noise and the 0.01 mm rounding)
// enters it through the window's two ends only, while its signal grows with the window's
// displacement. Per sample (M = 1) that noise is half of phi's variance at 1.3 ms and least
// squares found Ke 40-52 % low (errors in variables); over M samples the attenuation falls as
// 1/M^2. The PID's derivative term telescopes in the sum of u too, which leaves u's share of
// the gap noise at Kp's instead of Kp Td / Ts. Covariance: sandwich whose score is carried per
// sample (window_rows_of_samples: the windows' overlap exactly), with the per-sample residuals'
// autocovariance by Bartlett weights over 6 lags (a sample's x, i and u noise reach its
// neighbour's equation: lag 1, negative where the gap's noise telescopes). With the windowed
// residuals' autocovariance over the overlap instead (until 2026-12-03) the sigma of Ke at the
// point was a quarter to half too small on the rig's records: over 20 seeds at 1.3, 1.5, 3.25,
// 4 ms the rms of error / sigma was 1.26, 1.78, 1.20, 1.22; now 0.85, 1.16, 1.00, 1.08 (lags 3:
// 0.77-1.08, 12: 0.93-1.33), the mean sigma 2.4, 2.5, 1.8, 1.3 % against the information bound
// of 2.2, 2.3, 1.4, 1.0 % with the motion known exactly.
Coil fit_coil(const MaglevGreyBoxInput& in, const Estimates& e, Index M) {
  const Index n = in.x.size() - 1;
  Eigen::MatrixXd per_sample(n, 3);
  Eigen::VectorXd next = in.i.tail(n);
  for (Index k = 0; k < n; ++k) per_sample.row(k) << in.i(k), in.u(k), emf_regressor(in, k, e);
  const Index rows = n - M + 1;
  if (rows < 10) throw InsufficientData(kGreyboxWho + ": the record is too short for the coil's windows");
  Eigen::MatrixXd A(rows, 3);
  Eigen::VectorXd b(rows);
  A.row(0) = per_sample.topRows(M).colwise().sum();
  b(0) = next.head(M).sum();
  for (Index k = 1; k < rows; ++k) {  // running sums
    A.row(k) = A.row(k - 1) + per_sample.row(k + M - 1) - per_sample.row(k - 1);
    b(k) = b(k - 1) + next(k + M - 1) - next(k - 1);
  }
  const Eigen::Vector3d scale = A.colwise().norm().transpose();
  if (!(scale.array() > 0.0).all())
    throw InsufficientData(kGreyboxWho + ": the coil regression has a zero column (constant current, command or gap)");
  const Eigen::MatrixXd As = A * scale.cwiseInverse().asDiagonal();
  const auto solution = linalg::qr_solve(As, b);
  if (solution.rank < 3)
    throw InsufficientData(kGreyboxWho + ": the coil regression is rank deficient (rank " +
                           std::to_string(solution.rank) + " of 3)");
  const Eigen::MatrixXd gram = linalg::qr_inverse_gram(As);
  if (gram.size() == 0) throw InsufficientData(kGreyboxWho + ": the coil regression is rank deficient");
  Coil c;
  const Eigen::Vector3d theta = solution.x.cwiseQuotient(scale);
  c.a = theta(0);
  c.beta = theta(1);
  c.gamma = theta(2);
  const Eigen::VectorXd residual = next - per_sample * theta;  // per sample
  c.residual_rms = std::sqrt(residual.squaredNorm() / double(n));
  const Eigen::MatrixXd scaled_cov = gram * score_covariance(window_rows_of_samples(As, n), residual, 6) * gram;
  c.covariance = scale.cwiseInverse().asDiagonal() * scaled_cov * scale.cwiseInverse().asDiagonal();
  if (!(c.a > 0.0 && c.a < 1.0) || !(c.beta > 0.0)) {
    std::ostringstream msg;
    msg << kGreyboxWho << ": the coil fit gives a = " << c.a << ", beta = " << c.beta
        << " (a pole outside (0, 1) or no gain): the record does not support the coil model";
    throw InsufficientData(msg.str());
  }
  return c;
}

// R, L, Ke from (a, beta, gamma): the EMF enters i[k+1] as (1/L) n_i Ke phi[k].
Eigen::Vector3d coil_physical(const Eigen::Vector3d& p, double Ts, double kw, double n_i) {
  const double R = kw * (1.0 - p(0)) / p(1), L = -R * Ts / std::log(p(0));
  return {R, L, p(2) * L / n_i};
}

// The body's windows: per sample interval j and node q the log ratios of i and x to the
// operating point and the node's time; per window k its left side.
struct Body {
  Index m = 0;
  double Ts = 0, g = 0;
  Eigen::MatrixXd li, lx;  // intervals x 4
  std::vector<Index> centres;
  Eigen::VectorXd lhs;  // per centre: x[k+m] - 2 x[k] + x[k-m] - g (m Ts)^2
};

Body body_windows(const MaglevGreyBoxInput& in, const Estimates& e) {
  const Index N = in.x.size();
  Body b;
  b.Ts = in.sample_time;
  b.g = e.g;
  b.m = std::max<Index>(2, Index(std::llround(in.window / in.sample_time)));
  if (N < 2 * b.m + 4)
    throw InsufficientData(kGreyboxWho + ": " + std::to_string(N) + " samples are too few for windows of " +
                           std::to_string(2 * b.m) + " samples");
  b.li.resize(N - 1, 4);
  b.lx.resize(N - 1, 4);
  std::vector<bool> usable(std::size_t(N - 1), true);
  for (Index j = 0; j + 1 < N; ++j) {
    const SampleMotion motion(in, j, e);
    for (int q = 0; q < 4; ++q) {
      const double s = kNode[std::size_t(q)];
      const double current = motion.current(s), gap = motion.gap(s);
      if (!(current > 0.0) || !(gap > 0.0)) usable[std::size_t(j)] = false;
      b.li(j, q) = current > 0.0 ? std::log(current / in.i0) : 0.0;
      b.lx(j, q) = gap > 0.0 ? std::log(in.x0 / gap) : 0.0;
    }
  }
  const double M = double(b.m) * b.Ts;
  for (Index k = b.m + 1; k + b.m <= N - 2; ++k) {
    bool ok = true;
    for (Index j = k - b.m; j < k + b.m; ++j) ok = ok && usable[std::size_t(j)];
    if (!ok) continue;
    b.centres.push_back(k);
  }
  b.lhs.resize(Index(b.centres.size()));
  for (std::size_t c = 0; c < b.centres.size(); ++c) {
    const Index k = b.centres[c];
    b.lhs(Index(c)) = in.x(k + b.m) - 2 * in.x(k) + in.x(k - b.m) - e.g * M * M;
  }
  return b;
}

// r_k = lhs_k + g rho sum K w (i/i0)^n_i (x0/x)^n_x and its Jacobian in (rho, n_i, n_x).
void body_residuals(const Body& b, const double* theta, double* r, double* jac) {
  const double rho = theta[0], n_i = theta[1], n_x = theta[2], M = double(b.m) * b.Ts;
  for (std::size_t c = 0; c < b.centres.size(); ++c) {
    const Index k = b.centres[c];
    double s = 0, s_i = 0, s_x = 0;
    for (Index j = k - b.m; j < k + b.m; ++j)
      for (int q = 0; q < 4; ++q) {
        const double t = (double(j - k) + kNode[std::size_t(q)]) * b.Ts;
        const double w = (M - std::abs(t)) * kWeight[std::size_t(q)] * b.Ts;
        const double f = w * std::exp(n_i * b.li(j, q) + n_x * b.lx(j, q));
        s += f;
        s_i += f * b.li(j, q);
        s_x += f * b.lx(j, q);
      }
    r[c] = b.lhs(Index(c)) + b.g * rho * s;
    if (jac) {
      jac[3 * c] = b.g * s;
      jac[3 * c + 1] = b.g * rho * s_i;
      jac[3 * c + 2] = b.g * rho * s_x;
    }
  }
}

}  // namespace

MaglevGreyBoxFit fit_maglev_greybox(const MaglevGreyBoxInput& in) {
  const Index N = in.x.size();
  if (in.i.size() != N || in.u.size() != N)
    throw Error(kGreyboxWho + ": x, i and u must have one entry per sample (" + std::to_string(N) + ", " +
                std::to_string(in.i.size()) + ", " + std::to_string(in.u.size()) + ")");
  if (!in.x.allFinite() || !in.i.allFinite() || !in.u.allFinite())
    throw Error(kGreyboxWho + ": a signal is not finite");
  if ((in.x.array() <= 0.0).any()) throw Error(kGreyboxWho + ": the gap x must be positive in every sample");
  if (!(in.sample_time > 0.0) || !(in.x0 > 0.0) || !(in.i0 > 0.0) || !(in.window > 0.0) || !(in.coil_window >= 0.0) ||
      !(in.tolerance > 0.0)) {
    std::ostringstream msg;
    msg << kGreyboxWho
        << ": sample time, operating gap, operating current, windows and tolerance must be positive, got "
        << in.sample_time << ", " << in.x0 << ", " << in.i0 << ", " << in.window << ", " << in.coil_window << ", "
        << in.tolerance;
    throw Error(msg.str());
  }
  if (N < 20) throw InsufficientData(kGreyboxWho + ": " + std::to_string(N) + " samples are too few");
  const double m = nominal_value(in, "m"), g = nominal_value(in, "g"), kw = nominal_value(in, "kw");
  double n_i = nominal_value(in, "n_i"), n_x = nominal_value(in, "n_x");
  const double Ts = in.sample_time;

  const Index coil_samples = std::max<Index>(1, Index(std::llround(in.coil_window / Ts)));
  MaglevGreyBoxFit out;
  out.coil_window_samples = coil_samples;
  NonlinearLeastSquaresSolution solution;
  Coil coil;
  Eigen::Vector3d coil_values;
  // The coil's back-EMF regressor and the body's motion within a sample use each other's
  // estimates: three passes (the third changes the second's parameters by ~1e-6).
  Estimates est{nominal_value(in, "R"), nominal_value(in, "L"), nominal_value(in, "Ke"), kw, n_i, n_x, 1.0, g};
  for (int pass = 0; pass < 3; ++pass) {
    coil = fit_coil(in, est, coil_samples);
    coil_values = coil_physical({coil.a, coil.beta, coil.gamma}, Ts, kw, est.n_i);
    est.R = coil_values(0);
    est.L = coil_values(1);
    est.Ke = std::max(coil_values(2), 0.0);
    const Body body = body_windows(in, est);
    if (body.centres.size() < 10) throw InsufficientData(kGreyboxWho + ": fewer than 10 usable windows for the body");
    NonlinearLeastSquares problem;
    problem.residual_count = int(body.centres.size());
    problem.residuals = [&body](const double* theta, double* r, double* jac) {
      body_residuals(body, theta, r, jac);
      return true;
    };
    problem.lower = Eigen::Vector3d(1e-3, 0.05, 0.05);
    problem.upper = Eigen::Vector3d(1e3, 10.0, 10.0);
    NonlinearLeastSquaresOptions options;
    options.max_iterations = 100;
    options.jacobian = true;
    solution = solve_nonlinear_least_squares(problem, Eigen::Vector3d(est.rho, est.n_i, est.n_x), options);
    if (!solution.usable() || !solution.evaluated)
      throw InsufficientData(kGreyboxWho + ": the body fit failed: " + solution.message);
    est.rho = solution.x(0);
    est.n_i = n_i = solution.x(1);
    est.n_x = n_x = solution.x(2);
    out.window_samples = body.m;
    out.iterations += solution.iterations;
  }

  // Body covariance: sandwich with the residual autocovariance over the windows' overlap.
  const Eigen::MatrixXd& J = solution.jacobian;
  const Eigen::VectorXd& r = solution.residuals;
  const Eigen::MatrixXd H_inv = linalg::qr_inverse_gram(J);
  if (H_inv.size() == 0)
    throw InsufficientData(kGreyboxWho +
                           ": the body fit is rank deficient (rho, n_i, n_x not separable in this record)");
  const Eigen::Matrix3d body_cov = H_inv * score_covariance(J, r, 2 * out.window_samples) * H_inv;

  // Coil covariance through R, L, Ke (central differences of coil_physical).
  const Eigen::Vector3d p(coil.a, coil.beta, coil.gamma);
  Eigen::Matrix3d G;
  for (int c = 0; c < 3; ++c) {
    const double h = 1e-6 * std::max(std::abs(p(c)), 1e-12);
    Eigen::Vector3d up = p, down = p;
    up(c) += h;
    down(c) -= h;
    G.col(c) = (coil_physical(up, Ts, kw, n_i) - coil_physical(down, Ts, kw, n_i)) / (2 * h);
  }
  const Eigen::Matrix3d coil_cov = G * coil.covariance * G.transpose();

  const double rho = solution.x(0);
  const double Km = rho * m * g * std::pow(in.x0, n_x) / std::pow(in.i0, n_i);
  // d ln Km = d rho / rho + ln x0 d n_x - ln i0 d n_i
  const Eigen::Vector3d dlnKm(1.0 / rho, -std::log(in.i0), std::log(in.x0));
  auto put = [&](const std::string& name, double value, double variance) {
    out.value[name] = value;
    out.sigma[name] = std::sqrt(std::max(variance, 0.0));
    if (!(out.sigma[name] <= 0.5 * std::abs(value))) out.unsupported.push_back(name);
    if (!(3.0 * out.sigma[name] <= in.tolerance * std::abs(value))) out.unresolved.push_back(name);
  };
  put("R", coil_values(0), coil_cov(0, 0));
  put("L", coil_values(1), coil_cov(1, 1));
  // Ke carries m^n_x / A^(n_i-1) like Km: the coil fits n_i Ke i0^(n_i-1) / x0^n_x, so the
  // exponents' uncertainty moves it too, d ln Ke = ln x0 d n_x - (ln i0 + 1/n_i) d n_i (at
  // 1.3-1.5 ms that is most of its sigma: an n_x 0.6 % off moved Ke 11 %).
  const Eigen::Vector3d dlnKe(0.0, -std::log(in.i0) - 1.0 / n_i, std::log(in.x0));
  put("Ke", coil_values(2), coil_cov(2, 2) + coil_values(2) * coil_values(2) * dlnKe.dot(body_cov * dlnKe));
  // At the operating point the exponents' share cancels but for n_i's own factor (Ke = gamma L / n_i).
  const double at_point = std::pow(in.i0, n_i - 1.0) / std::pow(in.x0, n_x);
  put("Ke_at_point", coil_values(2) * at_point,
      at_point * at_point * (coil_cov(2, 2) + coil_values(2) * coil_values(2) * body_cov(1, 1) / (n_i * n_i)));
  put("rho", rho, body_cov(0, 0));
  put("n_i", n_i, body_cov(1, 1));
  put("n_x", n_x, body_cov(2, 2));
  put("Km", Km, Km * Km * dlnKm.dot(body_cov * dlnKm));
  // At the operating point with the force constant closed by gravity balance (rho = 1 there).
  put("stiffness", n_x * g / in.x0, std::pow(g / in.x0, 2) * body_cov(2, 2));
  put("current_gain", n_i * g / in.i0, std::pow(g / in.i0, 2) * body_cov(1, 1));
  // Its sigma through the body's and the coil's covariances (central differences of 1e-4
  // relative: an eigenvalue's rounding at 1e-6 moved the sigma by 3e-9 between a record and its
  // MAT import; the two steps taken as independent).
  Eigen::VectorXd q(6);
  q << rho, n_i, n_x, coil_values(0), coil_values(1), coil_values(2);
  Eigen::MatrixXd q_cov = Eigen::MatrixXd::Zero(6, 6);
  q_cov.topLeftCorner(3, 3) = body_cov;
  q_cov.bottomRightCorner(3, 3) = coil_cov;
  Eigen::RowVectorXd dpole(6);
  for (Index c = 0; c < 6; ++c) {
    const double h = 1e-4 * std::max(std::abs(q(c)), 1e-12);
    Eigen::VectorXd up = q, down = q;
    up(c) += h;
    down(c) -= h;
    dpole(c) =
        (linearised_unstable_pole(up, g, in.x0, in.i0) - linearised_unstable_pole(down, g, in.x0, in.i0)) / (2 * h);
  }
  put("unstable_pole", linearised_unstable_pole(q, g, in.x0, in.i0), (dpole * q_cov * dpole.transpose())(0, 0));
  out.coil_residual_rms = coil.residual_rms;
  out.body_residual_rms = std::sqrt(r.squaredNorm() / double(r.size()));
  return out;
}

}  // namespace ambid::ident
