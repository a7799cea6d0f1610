#pragma once
// Sensitivity functions of the loop, in the experiment contract's sign u = K y + d (K inputs x
// outputs; d a disturbance at the plant input). ISO 14839-3 breaks the loop at the plant input:
//   input sensitivity   S_u = (I - K G)^-1   (from d to u; its diagonal entry i is the loop
//                                             broken at input i with the other loops closed),
//   output sensitivity  S_y = (I - G K)^-1.
// With a reference entering as u = K y + M r, the measured response from r to u is S_u M, so
// S_u is measured directly, without a plant model: S_u = T_ur M^+.
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/experiment.hpp"
#include "core/state_space.hpp"
#include "identifier/frequency_domain/frf_loop.hpp"
#include "identifier/frf_types.hpp"
#include "identifier/iso_14839.hpp"

namespace ambid::ident {

// Throw Error on inconsistent sizes and InsufficientData when I - K G (I - G K) is singular.
Eigen::MatrixXcd input_sensitivity(const Eigen::MatrixXcd& G, const Eigen::MatrixXcd& K);
Eigen::MatrixXcd output_sensitivity(const Eigen::MatrixXcd& G, const Eigen::MatrixXcd& K);

// S_u from a plant FRF (outputs x inputs) and the recorded controller, line by line.
Frf input_sensitivity(const Frf& plant, const StateSpaceController& controller, const LoopSignalNames& signals);
// S_u from a discrete plant model and the recorded controller on a frequency grid (Hz).
Frf input_sensitivity(const DiscreteSystem& plant, const StateSpaceController& controller,
                      const LoopSignalNames& signals, const Eigen::VectorXd& frequency_hz);
// S_u measured: T_ur M^+ from the response of the plant inputs to the references (variance
// carried over when M is the identity, as when r is added to the controller output).
Frf input_sensitivity_from_reference(const Frf& input_from_reference, const StateSpaceController& controller,
                                     const LoopSignalNames& signals);

// The peak of one loop over the lines of an FRF (the largest value on the grid: the grid must
// resolve the peak) and its ISO 14839-3 zone.
struct SensitivityPeak {
  std::string loop;
  double frequency_hz = 0.0;
  double magnitude = 0.0;
  double magnitude_db = 0.0;
  IsoZone zone = IsoZone::A;
};

// One peak per diagonal entry of S (loop_names names them, one per row; Error otherwise).
std::vector<SensitivityPeak> sensitivity_peaks(const Frf& S, const std::vector<std::string>& loop_names,
                                               const IsoZoneLimits& limits = {});
// The peak of the largest singular value of S (all loops together), named `loop`.
SensitivityPeak max_singular_sensitivity_peak(const Frf& S, const std::string& loop = "sigma_max",
                                              const IsoZoneLimits& limits = {});

}  // namespace ambid::ident
