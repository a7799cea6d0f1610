#pragma once
// The recorded controller seen from the plant: at one frequency, the contract controller
// (uf = Kc v, v the deviations of its named inputs, u = uf + r) is solved for the plant input,
//   u = K y + M r,
// with K (inputs x outputs) the feedback and M (inputs x references) how the excitation reaches
// the plant input. The controller may read plant inputs (an observer uses the applied u) and
// even references; those paths are folded in: with uf = Ky y + Ku u + Kr r and u = P uf + E r
// (P places the controller outputs among the plant inputs, E puts reference j on the plant
// input named by controller output j), K = (I - P Ku)^-1 P Ky and M = (I - P Ku)^-1 (P Kr + E).
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/experiment.hpp"

namespace ambid::ident {

// Names of the signals of the loop, in the column order of the data (Experiment y/u/r names).
struct LoopSignalNames {
  std::vector<std::string> y, u, r;
};

struct LoopResponse {
  Eigen::MatrixXcd K;  // inputs x outputs
  Eigen::MatrixXcd M;  // inputs x references
};

// Throws Error when a controller input or output is not a signal of the loop, the number of
// references differs from the number of controller outputs (reference j is added to output j),
// or I - P Ku is singular at w (names the frequency).
LoopResponse loop_response(const StateSpaceController& controller, const LoopSignalNames& signals, double omega);

}  // namespace ambid::ident
