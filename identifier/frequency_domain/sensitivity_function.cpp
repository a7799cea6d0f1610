#include "identifier/frequency_domain/sensitivity_function.hpp"

#include <cmath>
#include <numbers>
#include <string>

#include "core/error.hpp"
#include "identifier/frequency_domain/freq_response.hpp"
#include "identifier/frequency_domain/frf_linalg.hpp"

namespace ambid::ident {
namespace {

double omega_of(double f) { return 2.0 * std::numbers::pi * f; }

Eigen::MatrixXcd inverse_of(const Eigen::MatrixXcd& X, const char* what) {
  if (const double ic = inverse_condition(X); !(ic > 1e-13))
    throw InsufficientData(std::string(what) + " is singular (inverse condition " + std::to_string(ic) + ")");
  return left_solve(X, Eigen::MatrixXcd::Identity(X.rows(), X.rows()));
}

void check_sizes(const Eigen::MatrixXcd& G, const Eigen::MatrixXcd& K) {
  if (K.rows() != G.cols() || K.cols() != G.rows())
    throw Error("sensitivity: K must be " + std::to_string(G.cols()) + "x" + std::to_string(G.rows()) +
                " (inputs x outputs) for G " + std::to_string(G.rows()) + "x" + std::to_string(G.cols()) + ", got " +
                std::to_string(K.rows()) + "x" + std::to_string(K.cols()));
}

SensitivityPeak peak_of(const Eigen::VectorXd& f, const Eigen::VectorXd& magnitude, const std::string& loop,
                        const IsoZoneLimits& limits) {
  if (magnitude.size() == 0) throw Error("sensitivity peak: the response has no lines");
  Eigen::Index at = 0;
  magnitude.maxCoeff(&at);
  SensitivityPeak p;
  p.loop = loop;
  p.frequency_hz = f(at);
  p.magnitude = magnitude(at);
  p.magnitude_db = magnitude_db(p.magnitude);
  p.zone = iso14839_zone(p.magnitude_db, limits);
  return p;
}

}  // namespace

Eigen::MatrixXcd input_sensitivity(const Eigen::MatrixXcd& G, const Eigen::MatrixXcd& K) {
  check_sizes(G, K);
  return inverse_of(Eigen::MatrixXcd::Identity(G.cols(), G.cols()) - K * G, "input sensitivity: I - K G");
}

Eigen::MatrixXcd output_sensitivity(const Eigen::MatrixXcd& G, const Eigen::MatrixXcd& K) {
  check_sizes(G, K);
  return inverse_of(Eigen::MatrixXcd::Identity(G.rows(), G.rows()) - G * K, "output sensitivity: I - G K");
}

Frf input_sensitivity(const Frf& plant, const StateSpaceController& controller, const LoopSignalNames& signals) {
  plant.validate();
  Frf out;
  out.frequency_hz = plant.frequency_hz;
  for (Eigen::Index l = 0; l < plant.lines(); ++l) {
    const double f = plant.frequency_hz(l);
    const LoopResponse loop = loop_response(controller, signals, omega_of(f));
    try {
      out.value.push_back(input_sensitivity(plant.value[static_cast<std::size_t>(l)], loop.K));
    } catch (const InsufficientData& e) {
      throw InsufficientData(std::string(e.what()) + " at " + std::to_string(f) + " Hz");
    }
  }
  return out;
}

Frf input_sensitivity(const DiscreteSystem& plant, const StateSpaceController& controller,
                      const LoopSignalNames& signals, const Eigen::VectorXd& frequency_hz) {
  if (std::abs(plant.sample_time - controller.sample_time) > 1e-9 * plant.sample_time)
    throw Error("input sensitivity: plant sample time " + std::to_string(plant.sample_time) +
                " differs from the controller's " + std::to_string(controller.sample_time));
  return input_sensitivity(freq_response(plant, frequency_hz), controller, signals);
}

Frf input_sensitivity_from_reference(const Frf& Tur, const StateSpaceController& controller,
                                     const LoopSignalNames& signals) {
  Tur.validate();
  Frf out;
  out.frequency_hz = Tur.frequency_hz;
  bool identity_m = true;
  for (Eigen::Index l = 0; l < Tur.lines(); ++l) {
    const double f = Tur.frequency_hz(l);
    const LoopResponse loop = loop_response(controller, signals, omega_of(f));
    const Eigen::MatrixXcd& T = Tur.value[static_cast<std::size_t>(l)];
    if (T.rows() != loop.M.rows() || T.cols() != loop.M.cols())
      throw Error("input sensitivity: T_ur is " + std::to_string(T.rows()) + "x" + std::to_string(T.cols()) +
                  ", expected inputs x references " + std::to_string(loop.M.rows()) + "x" +
                  std::to_string(loop.M.cols()));
    if (!(inverse_condition(loop.M) > 1e-12))
      throw InsufficientData("input sensitivity: the references do not reach every plant input at " +
                             std::to_string(f) + " Hz");
    if (loop.M.rows() != loop.M.cols() || !loop.M.isIdentity(1e-12)) identity_m = false;
    out.value.push_back(right_solve(T, loop.M));
  }
  if (identity_m && Tur.has_variance()) {
    out.variance = Tur.variance;
    out.variance_dof = Tur.variance_dof;
  }
  return out;
}

std::vector<SensitivityPeak> sensitivity_peaks(const Frf& S, const std::vector<std::string>& loop_names,
                                               const IsoZoneLimits& limits) {
  S.validate();
  if (S.rows() != S.cols())
    throw Error("sensitivity peaks: S must be square, got " + std::to_string(S.rows()) + "x" +
                std::to_string(S.cols()));
  if (static_cast<Eigen::Index>(loop_names.size()) != S.rows())
    throw Error("sensitivity peaks: " + std::to_string(loop_names.size()) + " loop names for " +
                std::to_string(S.rows()) + " loops");
  std::vector<SensitivityPeak> out;
  for (Eigen::Index i = 0; i < S.rows(); ++i)
    out.push_back(peak_of(S.frequency_hz, S.element(i, i).cwiseAbs(), loop_names[static_cast<std::size_t>(i)], limits));
  return out;
}

SensitivityPeak max_singular_sensitivity_peak(const Frf& S, const std::string& loop, const IsoZoneLimits& limits) {
  S.validate();
  Eigen::VectorXd sigma(S.lines());
  for (Eigen::Index l = 0; l < S.lines(); ++l) sigma(l) = max_singular_value(S.value[static_cast<std::size_t>(l)]);
  return peak_of(S.frequency_hz, sigma, loop, limits);
}

}  // namespace ambid::ident
