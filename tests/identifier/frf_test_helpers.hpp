#pragma once
// Shared by tests/identifier/frf_*, sensitivity_*, iso_*, rational_fit_* tests (header only,
// so the other identifier tests do not link it): a Sales rotor loop (seed 003 eq. 8) closed by
// a filtered PD controller, a random-phase multisine, and a sample-exact linear closed-loop
// simulation in the experiment contract's form (u = uf + r, uf from the recorded controller).
#include <cmath>
#include <complex>
#include <cstdint>
#include <cstdio>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/experiment.hpp"
#include "core/linalg.hpp"
#include "core/state_space.hpp"
#include "identifier/frequency_domain/frf_loop.hpp"

namespace ambid::ident::test {

inline constexpr double kPi = std::numbers::pi;

// Seed 003 eq. 8: A = [0 1; 2800 0], B = [0; 4.2], C = [200 0]; G(s) = 840 / (s^2 - 2800).
inline ContinuousSystem sales_rotor_system() {
  ContinuousSystem s;
  s.A = (Eigen::MatrixXd(2, 2) << 0.0, 1.0, 2800.0, 0.0).finished();
  s.B = (Eigen::MatrixXd(2, 1) << 0.0, 4.2).finished();
  s.C = (Eigen::MatrixXd(1, 2) << 200.0, 0.0).finished();
  s.D = Eigen::MatrixXd::Zero(1, 1);
  return s;
}

// Continuous controller K(s) = -(kp + kd s / (tau s + 1)) (negative PD in the contract's
// positive-feedback sign), discretised by ZOH: closed-loop poles near 150 rad/s, zeta 0.7.
inline StateSpaceController sales_pd_controller(double T, double kp = 30.12, double kd = 0.25, double tau = 5e-4) {
  ContinuousSystem k;
  k.A = Eigen::MatrixXd::Constant(1, 1, -1.0 / tau);
  k.B = Eigen::MatrixXd::Constant(1, 1, 1.0);
  k.C = Eigen::MatrixXd::Constant(1, 1, kd / (tau * tau));
  k.D = Eigen::MatrixXd::Constant(1, 1, -(kp + kd / tau));
  const DiscreteSystem kd_sys = c2d_zoh(k, T);
  StateSpaceController c;
  c.sample_time = T;
  c.inputs = {"y"};
  c.outputs = {"u"};
  c.A = kd_sys.A;
  c.B = kd_sys.B;
  c.C = kd_sys.C;
  c.D = kd_sys.D;
  return c;
}

// Closed forms of the zero-order-hold equivalents at z (independent of c2d_zoh):
// plant 840 / (s^2 - a^2), a^2 = 2800: G(s)/s = -0.3/s + 0.15/(s - a) + 0.15/(s + a), so
// G_d(z) = -0.3 + 0.15 (z - 1)/(z - e^{aT}) + 0.15 (z - 1)/(z - e^{-aT});
inline std::complex<double> sales_rotor_zoh(std::complex<double> z, double T) {
  const double a = std::sqrt(2800.0);
  return -0.3 + 0.15 * (z - 1.0) / (z - std::exp(a * T)) + 0.15 * (z - 1.0) / (z - std::exp(-a * T));
}
// controller -(kp + kd/tau) + (kd/tau^2) / (s + 1/tau): K_d(z) = D + (kd/tau) (1 - e^{-T/tau}) / (z - e^{-T/tau}).
inline std::complex<double> sales_pd_zoh(std::complex<double> z, double T, double kp = 30.12, double kd = 0.25,
                                         double tau = 5e-4) {
  const double e = std::exp(-T / tau);
  return -(kp + kd / tau) + (kd / tau) * (1.0 - e) / (z - e);
}

inline LoopSignalNames sales_signals() { return LoopSignalNames{{"y"}, {"u"}, {"r"}}; }

// n samples of seeded white Gaussian noise of the given std, one column.
inline Eigen::MatrixXd gaussian(Eigen::Index n, double std, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, std);
  Eigen::MatrixXd r(n, 1);
  for (Eigen::Index k = 0; k < n; ++k) r(k, 0) = normal(rng);
  return r;
}

// One period (N samples) of a random-phase multisine with unit amplitude on each line.
inline Eigen::VectorXd multisine_period(Eigen::Index N, const std::vector<Eigen::Index>& lines, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> phase(0.0, 2.0 * kPi);
  Eigen::VectorXd s = Eigen::VectorXd::Zero(N);
  for (const Eigen::Index k : lines) {
    const double phi = phase(rng);
    for (Eigen::Index n = 0; n < N; ++n)
      s(n) += std::cos(2.0 * kPi * static_cast<double>(k * n) / static_cast<double>(N) + phi);
  }
  return s;
}

// `periods` copies of the period scaled to rms `level`, on `channels` columns: all equal for one
// channel; channel j of period p multiplied by H(j, p mod P) for the Hadamard pattern (P = 2 or
// 4), each channel with its own phases.
inline Eigen::MatrixXd multisine(Eigen::Index N, const std::vector<Eigen::Index>& lines, Eigen::Index periods,
                                 double level, int channels = 1, std::uint64_t seed = 7) {
  Eigen::MatrixXd H(1, 1);
  H << 1.0;
  while (H.rows() < channels) {
    const Eigen::Index h = H.rows();
    Eigen::MatrixXd H2(2 * h, 2 * h);
    H2 << H, H, H, -H;
    H = H2;
  }
  const Eigen::Index P = H.rows();
  Eigen::MatrixXd out(N * periods, channels);
  for (int c = 0; c < channels; ++c) {
    Eigen::VectorXd s = multisine_period(N, lines, seed + static_cast<std::uint64_t>(c));
    s *= level / std::sqrt(s.squaredNorm() / static_cast<double>(N));
    for (Eigen::Index p = 0; p < periods; ++p) out.block(p * N, c, N, 1) = H(c, p % P) * s;
  }
  return out;
}

struct LoopData {
  Eigen::MatrixXd y, u;
};

// Sample-exact closed loop: plant x[k+1] = A x + B (u + w), y = C x + v (v, w white Gaussian
// with the given standard deviations; y is what the controller receives and what is recorded),
// controller from the contract (its inputs name signals of `signals`), u = uf + r. The plant
// must have D = 0.
inline LoopData simulate_loop(const DiscreteSystem& plant, const StateSpaceController& K,
                              const LoopSignalNames& signals, const Eigen::MatrixXd& r, double y_noise_std = 0.0,
                              double u_noise_std = 0.0, std::uint64_t seed = 1) {
  const Eigen::Index N = r.rows(), ny = plant.outputs(), nu = plant.inputs();
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(plant.states()), xc = Eigen::VectorXd::Zero(K.states());
  LoopData out{Eigen::MatrixXd(N, ny), Eigen::MatrixXd(N, nu)};
  Eigen::VectorXd v(static_cast<Eigen::Index>(K.inputs.size()));
  for (Eigen::Index k = 0; k < N; ++k) {
    Eigen::VectorXd y = plant.C * x;
    for (Eigen::Index i = 0; i < ny; ++i) y(i) += y_noise_std * normal(rng);
    // uf does not depend on u[k] (D has zero u columns): evaluate with u = 0 first.
    auto value_of = [&](const std::string& name, const Eigen::VectorXd& u) {
      for (Eigen::Index i = 0; i < ny; ++i)
        if (signals.y[static_cast<std::size_t>(i)] == name) return y(i);
      for (Eigen::Index i = 0; i < nu; ++i)
        if (signals.u[static_cast<std::size_t>(i)] == name) return u(i);
      for (Eigen::Index i = 0; i < r.cols(); ++i)
        if (signals.r[static_cast<std::size_t>(i)] == name) return r(k, i);
      return 0.0;
    };
    Eigen::VectorXd u = Eigen::VectorXd::Zero(nu);
    for (std::size_t c = 0; c < K.inputs.size(); ++c) v(static_cast<Eigen::Index>(c)) = value_of(K.inputs[c], u);
    const Eigen::VectorXd uf = K.C * xc + K.D * v;
    for (std::size_t o = 0; o < K.outputs.size(); ++o)
      for (Eigen::Index i = 0; i < nu; ++i)
        if (signals.u[static_cast<std::size_t>(i)] == K.outputs[o])
          u(i) = uf(static_cast<Eigen::Index>(o)) + r(k, static_cast<Eigen::Index>(o));
    for (std::size_t c = 0; c < K.inputs.size(); ++c) v(static_cast<Eigen::Index>(c)) = value_of(K.inputs[c], u);
    out.y.row(k) = y.transpose();
    out.u.row(k) = u.transpose();
    Eigen::VectorXd w(nu);
    for (Eigen::Index i = 0; i < nu; ++i) w(i) = u_noise_std * normal(rng);
    xc = K.A * xc + K.B * v;
    x = plant.A * x + plant.B * (u + w);
  }
  return out;
}

// Largest eigenvalue modulus of the discrete closed loop of `plant` and a y-only controller
// (u = uf): stability check of a test loop.
inline double closed_loop_radius(const DiscreteSystem& plant, const StateSpaceController& K) {
  const Eigen::Index n = plant.states(), nc = K.states();
  Eigen::MatrixXd A(n + nc, n + nc);
  A << plant.A + plant.B * K.D * plant.C, plant.B * K.C, K.B * plant.C, K.A;
  return linalg::spectral_radius(A);
}

// For RecordProperty of small numbers (std::to_string prints 6 decimals only).
inline std::string scientific(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3e", value);
  return text;
}

inline double phase_deg(std::complex<double> z) { return std::arg(z) * 180.0 / kPi; }

// Phase difference a - b wrapped to (-180, 180] degrees.
inline double phase_error_deg(std::complex<double> a, std::complex<double> b) { return phase_deg(a / b); }

}  // namespace ambid::ident::test
