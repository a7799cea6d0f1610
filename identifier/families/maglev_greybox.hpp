#pragma once
// Grey-box fit of the physical parameters of `maglev1coil_voltage` (experiment-format.md,
// "Plant families"; maglev-rig.md) from a record of x, i and the commanded u. Both the gap and
// the coil current are measured, so the two equations are fitted apart, each on the whole
// nonlinear model (valid across reference levels, not linearised per level):
//
// 1. Coil: with u held by the DAC over a sample, the exact zero-order-hold solution is
//      i[k+1] = a i[k] + beta u[k] + gamma phi[k],   a = exp(-R Ts / L),  beta = kw (1 - a) / R,
//    phi[k] = i[k]^(n_i - 1) times the integral over the sample of exp(-(R/L)(Ts - t)) x'/x^n_x
//    (the back-EMF as the coil responds to it; x(t) and R/L of the previous pass),
//    gamma = n_i Ke / L. R, L, Ke follow with the nominal kw (the data cannot separate kw from
//    R and L). The equation is summed over windows of M samples (coil_window; every start):
//    the back-EMF regressor is the change of the law's potential over each sample, so the sum
//    telescopes and the logged gap's noise enters it at the window's two ends only. Per
//    sample, that noise attenuated Ke by least squares (errors in variables) by 40-52 % at
//    1.3-1.5 ms, 6-14 % at 3.25 ms on the rig's records. Linear least squares (QR with rank
//    check) on the windowed sums.
// 2. Body: the second difference over m samples equals the double integral of the acceleration,
//      x[k+m] - 2 x[k] + x[k-m] = sum over [t[k-m], t[k+m]] of (m Ts - |t - t[k]|) x''(t),
//      x'' = g - g rho (i / i0)^n_i (x0 / x)^n_x,
//    with (x0, i0) the operating point of the record and rho = 1 when gravity balances there.
//    The integral runs over 4 Gauss-Legendre nodes per sample, with i(t) between samples from
//    the coil model of step 1 (the electrical pole lies within a sample at the rig's rates) and
//    x(t) the chord between the logged gaps bent by the model's own acceleration
//    (maglev_greybox.cpp, SampleMotion): the acceleration jumps with the command at every
//    sample. rho, n_i, n_x by Levenberg-Marquardt. The left side carries the logger's rounding
//    of x once, however long the window: a window of m samples raises the signal by m^2 over a
//    second difference. Three passes of steps 1 and 2.
//
// m and kw come from the nominal parameters (the data cannot separate them from Km, R and L):
// Km = rho m g x0^n_x / i0^n_i. Uncertainty (one sigma): for both steps a sandwich with the
// residual autocovariance over the windows' overlap (the windows of neighbouring k share samples). Parameters whose
// sigma exceeds half their value are listed as not supported by the data, those whose three sigmas exceed the
// tolerance (relative) as not resolved to it. Nothing stabilises the linearised model: it keeps its unstable pole.
//
// The back-EMF is the weakest signal of the record: on the rig's records (13-16 mm, +-0.5 V of
// w) it is 2.6-9.5 mV rms against the 0.01 V logging of u (2.9 mV rms, white) and 10 uA of
// current noise, whose share of i[k+1] is larger than the back-EMF's. Even with the true motion
// known exactly, the information in 4000 samples bounds its sigma (Cramer-Rao, R and L fitted
// alongside) at 2.2 % at 1.3 ms, 2.3 % at 1.5 ms, 1.4 % at 3.25 ms and 1.0 % at 4 ms: no fit of
// these records pins Ke to 1 %, and this one says so (`unresolved`). What the coil equation
// determines is Ke at the operating point, Ke i0^(n_i-1) / x0^n_x (`Ke_at_point`); Ke itself
// carries m^n_x and adds the exponents' uncertainty times ln x0 (n_x 0.25 % off moves it 4 %).
#include <map>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace ambid::ident {

struct MaglevGreyBoxInput {
  double sample_time = 0.0;
  Eigen::VectorXd x, i, u;    // logged gap (m), current (A), command (V), one entry per sample
  double x0 = 0.0, i0 = 0.0;  // the operating point (measured, or the nominal model's)
  // Nominal m, g, kw (taken as known) and R, L, Km, Ke, n_i, n_x (starting values).
  std::map<std::string, double> nominal;
  double window = 0.02;  // s: half-width m Ts of the body's window (m at least 2)
  // s: the coil equation is summed over windows of coil_window / Ts samples (at least 1).
  double coil_window = 0.015;
  double tolerance = 0.01;  // relative: a parameter whose three sigmas exceed it is `unresolved`
};

struct MaglevGreyBoxFit {
  // R L Ke Ke_at_point Km n_i n_x rho stiffness current_gain unstable_pole
  std::map<std::string, double> value, sigma;
  std::vector<std::string> unsupported;  // parameters the data cannot support (sigma > value / 2)
  std::vector<std::string> unresolved;   // 3 sigma > tolerance |value| (the record cannot pin them that well)
  Eigen::Index window_samples = 0;       // m
  Eigen::Index coil_window_samples = 0;  // M
  double coil_residual_rms = 0.0;        // A
  double body_residual_rms = 0.0;        // m (of the windowed second difference)
  int iterations = 0;
};

// Error for missing nominal parameters, mismatched or non-finite signals, a non-positive
// operating point; InsufficientData when the record is too short for the window, the coil
// regression is rank deficient, its pole is not in (0, 1), or the body fit fails.
MaglevGreyBoxFit fit_maglev_greybox(const MaglevGreyBoxInput& input);

}  // namespace ambid::ident
