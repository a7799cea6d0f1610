#pragma once
// The signals of a closed-loop experiment as the identification methods use them: deviations
// from the operating point, columns in a chosen order, and the excitation r mapped to the
// plant input it is added to (experiment-format.md: u = uf + r, one r signal per controller
// output in order; without a controller, one per plant input in order).
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/experiment.hpp"

namespace ambid::ident {

struct LoopSignals {
  std::vector<std::string> y_names, u_names;
  Eigen::MatrixXd y;   // samples x outputs
  Eigen::MatrixXd u;   // samples x plant inputs (total plant input)
  Eigen::MatrixXd r;   // samples x plant inputs (zero where no excitation is added)
  Eigen::MatrixXd uf;  // u - r: the feedback part
};

// `y_names` / `u_names` choose (and order) the columns; each must be a signal of the
// experiment. Throws Error naming a missing signal (prefixed with `who`) or an r signal that
// cannot be placed.
LoopSignals loop_signals(const Experiment& experiment, const std::vector<std::string>& y_names,
                         const std::vector<std::string>& u_names, const std::string& who);
// All outputs and inputs in the experiment's own order.
LoopSignals loop_signals(const Experiment& experiment, const std::string& who);

}  // namespace ambid::ident
