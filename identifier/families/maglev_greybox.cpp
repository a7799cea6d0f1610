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
const std::string kWho = "maglev grey-box fit";

// 4-point Gauss-Legendre on [0, 1].
constexpr std::array<double, 4> kNode = {0.5 - 0.5 * 0.8611363115940526, 0.5 - 0.5 * 0.3399810435848563,
                                         0.5 + 0.5 * 0.3399810435848563, 0.5 + 0.5 * 0.8611363115940526};
constexpr std::array<double, 4> kWeight = {0.5 * 0.3478548451374538, 0.5 * 0.6521451548625461, 0.5 * 0.6521451548625461,
                                           0.5 * 0.3478548451374538};

double nominal_value(const MaglevGreyBoxInput& in, const char* name) {
  const auto it = in.nominal.find(name);
  if (it == in.nominal.end()) throw Error(kWho + ": nominal parameter '" + name + "' is missing");
  if (!(it->second > 0.0) || !std::isfinite(it->second)) {
    std::ostringstream msg;
    msg << kWho << ": nominal parameter '" << name << "' must be positive, got " << it->second;
    throw Error(msg.str());
  }
  return it->second;
}

// The gap within sample interval j at s in [0, 1] and its rate dx/ds: Catmull-Rom through
// x[j-1..j+2] (the end samples repeated at the record's ends).
struct GapCubic {
  double xm, x0, x1, x2;
  GapCubic(const Eigen::VectorXd& x, Index j)
      : xm(x(std::max<Index>(j - 1, 0))), x0(x(j)), x1(x(j + 1)), x2(x(std::min<Index>(j + 2, x.size() - 1))) {}
  double at(double s) const {
    return 0.5 * (2 * x0 + (-xm + x1) * s + (2 * xm - 5 * x0 + 4 * x1 - x2) * s * s +
                  (-xm + 3 * x0 - 3 * x1 + x2) * s * s * s);
  }
  double rate(double s) const {
    return 0.5 * ((-xm + x1) + 2 * (2 * xm - 5 * x0 + 4 * x1 - x2) * s + 3 * (-xm + 3 * x0 - 3 * x1 + x2) * s * s);
  }
};

// i^(n_i - 1) of the back-EMF, with the current floored at 1 % of the operating current: for
// n_i < 1 the family's flux diverges at zero current (the DAC clamped at 0 V empties the coil).
double emf_factor(double current, double n_i, double i0) {
  return std::pow(std::max(std::abs(current), 0.01 * i0), n_i - 1.0);
}

struct Coil {
  double a = 0, beta = 0, gamma = 0;
  Eigen::Matrix3d covariance;  // of (a, beta, gamma)
  double residual_rms = 0;
};

// The back-EMF regressor of sample k: i^(n_i-1) times the integral over the sample of
// x'/x^n_x weighted by the coil's response exp(-(R/L)(Ts - t)) (4 Gauss-Legendre nodes on the
// cubic through the logged gaps): the motion late in the sample counts more.
double emf_regressor(const MaglevGreyBoxInput& in, Index k, double n_i, double n_x, double decay) {
  const GapCubic cubic(in.x, k);
  const double Ts = in.sample_time;
  double sum = 0.0;
  for (int q = 0; q < 4; ++q) {
    const double s = kNode[std::size_t(q)];
    sum += kWeight[std::size_t(q)] * std::exp(-decay * Ts * (1.0 - s)) * cubic.rate(s) / std::pow(cubic.at(s), n_x);
  }
  return emf_factor(in.i(k), n_i, in.i0) * sum;  // the rate is per unit s: the Ts of dt cancels
}

// Step 1: i[k+1] = a i[k] + beta u[k] + gamma phi[k], columns equilibrated before the QR;
// `decay` the coil's R/L of the previous estimate.
Coil fit_coil(const MaglevGreyBoxInput& in, double n_i, double n_x, double decay) {
  const Index n = in.x.size() - 1;
  Eigen::MatrixXd A(n, 3);
  Eigen::VectorXd b = in.i.tail(n);
  for (Index k = 0; k < n; ++k) A.row(k) << in.i(k), in.u(k), emf_regressor(in, k, n_i, n_x, decay);
  const Eigen::Vector3d scale = A.colwise().norm().transpose();
  if (!(scale.array() > 0.0).all())
    throw InsufficientData(kWho + ": the coil regression has a zero column (constant current, command or gap)");
  const Eigen::MatrixXd As = A * scale.cwiseInverse().asDiagonal();
  const auto solution = linalg::qr_solve(As, b);
  if (solution.rank < 3)
    throw InsufficientData(kWho + ": the coil regression is rank deficient (rank " + std::to_string(solution.rank) +
                           " of 3)");
  const Eigen::MatrixXd gram = linalg::qr_inverse_gram(As);
  if (gram.size() == 0) throw InsufficientData(kWho + ": the coil regression is rank deficient");
  Coil c;
  const Eigen::Vector3d theta = solution.x.cwiseQuotient(scale);
  c.a = theta(0);
  c.beta = theta(1);
  c.gamma = theta(2);
  const Eigen::VectorXd r = b - A * theta;
  c.residual_rms = std::sqrt(r.squaredNorm() / double(n));
  const double s2 = r.squaredNorm() / double(n - 3);
  c.covariance = scale.cwiseInverse().asDiagonal() * gram * scale.cwiseInverse().asDiagonal() * s2;
  if (!(c.a > 0.0 && c.a < 1.0) || !(c.beta > 0.0)) {
    std::ostringstream msg;
    msg << kWho << ": the coil fit gives a = " << c.a << ", beta = " << c.beta
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

Body body_windows(const MaglevGreyBoxInput& in, double R, double L, double Ke, double kw, double n_i, double n_x,
                  double g) {
  const Index N = in.x.size();
  Body b;
  b.Ts = in.sample_time;
  b.g = g;
  b.m = std::max<Index>(2, Index(std::llround(in.window / in.sample_time)));
  if (N < 2 * b.m + 4)
    throw InsufficientData(kWho + ": " + std::to_string(N) + " samples are too few for windows of " +
                           std::to_string(2 * b.m) + " samples");
  b.li.resize(N - 1, 4);
  b.lx.resize(N - 1, 4);
  std::vector<bool> usable(std::size_t(N - 1), true);
  for (Index j = 0; j + 1 < N; ++j) {
    const double velocity = (in.x(j + 1) - in.x(j)) / b.Ts;
    const double emf = -n_i * Ke * emf_factor(in.i(j), n_i, in.i0) * velocity / std::pow(in.x(j), n_x);
    const double settled = (kw * in.u(j) - emf) / R;
    const GapCubic cubic(in.x, j);
    for (int q = 0; q < 4; ++q) {
      const double s = kNode[std::size_t(q)];
      const double current = settled + (in.i(j) - settled) * std::exp(-s * b.Ts * R / L);
      const double gap = cubic.at(s);
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
    b.lhs(Index(c)) = in.x(k + b.m) - 2 * in.x(k) + in.x(k - b.m) - g * M * M;
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
    throw Error(kWho + ": x, i and u must have one entry per sample (" + std::to_string(N) + ", " +
                std::to_string(in.i.size()) + ", " + std::to_string(in.u.size()) + ")");
  if (!in.x.allFinite() || !in.i.allFinite() || !in.u.allFinite()) throw Error(kWho + ": a signal is not finite");
  if ((in.x.array() <= 0.0).any()) throw Error(kWho + ": the gap x must be positive in every sample");
  if (!(in.sample_time > 0.0) || !(in.x0 > 0.0) || !(in.i0 > 0.0) || !(in.window > 0.0)) {
    std::ostringstream msg;
    msg << kWho << ": sample time, operating gap, operating current and window must be positive, got " << in.sample_time
        << ", " << in.x0 << ", " << in.i0 << ", " << in.window;
    throw Error(msg.str());
  }
  if (N < 20) throw InsufficientData(kWho + ": " + std::to_string(N) + " samples are too few");
  const double m = nominal_value(in, "m"), g = nominal_value(in, "g"), kw = nominal_value(in, "kw");
  double n_i = nominal_value(in, "n_i"), n_x = nominal_value(in, "n_x");
  nominal_value(in, "Ke");  // required like the others, though the fit starts without it
  const double Ts = in.sample_time;

  MaglevGreyBoxFit out;
  NonlinearLeastSquaresSolution solution;
  Coil coil;
  Eigen::Vector3d coil_values;
  // The coil's back-EMF regressor and the body's i(t) use each other's exponents: two passes.
  double decay = nominal_value(in, "R") / nominal_value(in, "L");
  for (int pass = 0; pass < 2; ++pass) {
    coil = fit_coil(in, n_i, n_x, decay);
    coil_values = coil_physical({coil.a, coil.beta, coil.gamma}, Ts, kw, n_i);
    decay = coil_values(0) / coil_values(1);
    const Body body = body_windows(in, coil_values(0), coil_values(1), std::max(coil_values(2), 0.0), kw, n_i, n_x, g);
    if (body.centres.size() < 10) throw InsufficientData(kWho + ": fewer than 10 usable windows for the body");
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
    solution = solve_nonlinear_least_squares(problem, Eigen::Vector3d(1.0, n_i, n_x), options);
    if (!solution.usable() || !solution.evaluated)
      throw InsufficientData(kWho + ": the body fit failed: " + solution.message);
    n_i = solution.x(1);
    n_x = solution.x(2);
    out.window_samples = body.m;
    out.iterations += solution.iterations;
  }

  // Body covariance: sandwich with the residual autocovariance over the windows' overlap.
  const Eigen::MatrixXd& J = solution.jacobian;
  const Eigen::VectorXd& r = solution.residuals;
  const Eigen::MatrixXd H_inv = linalg::qr_inverse_gram(J);
  if (H_inv.size() == 0)
    throw InsufficientData(kWho + ": the body fit is rank deficient (rho, n_i, n_x not separable in this record)");
  const Index lags = 2 * out.window_samples;
  Eigen::Matrix3d S = Eigen::Matrix3d::Zero();
  for (Index l = -lags; l <= lags; ++l) {
    const double bartlett = 1.0 - double(std::abs(l)) / double(lags + 1);
    for (Index k = std::max<Index>(0, -l); k < r.size() && k + l < r.size(); ++k)
      S += bartlett * (J.row(k).transpose() * r(k)) * (r(k + l) * J.row(k + l));
  }
  const Eigen::Matrix3d body_cov = H_inv * S * H_inv;

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
  };
  put("R", coil_values(0), coil_cov(0, 0));
  put("L", coil_values(1), coil_cov(1, 1));
  put("Ke", coil_values(2), coil_cov(2, 2));
  put("rho", rho, body_cov(0, 0));
  put("n_i", n_i, body_cov(1, 1));
  put("n_x", n_x, body_cov(2, 2));
  put("Km", Km, Km * Km * dlnKm.dot(body_cov * dlnKm));
  // At the operating point with the force constant closed by gravity balance (rho = 1 there).
  put("stiffness", n_x * g / in.x0, std::pow(g / in.x0, 2) * body_cov(2, 2));
  put("current_gain", n_i * g / in.i0, std::pow(g / in.i0, 2) * body_cov(1, 1));
  put("unstable_pole", std::sqrt(n_x * g / in.x0), g / in.x0 / (4 * n_x * g / in.x0) * body_cov(2, 2) * g / in.x0);
  out.coil_residual_rms = coil.residual_rms;
  out.body_residual_rms = std::sqrt(r.squaredNorm() / double(r.size()));
  return out;
}

}  // namespace ambid::ident
