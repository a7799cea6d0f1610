#include "diagnostics/audit/maglev_dac_replay.hpp"

#include <algorithm>

#include "core/error.hpp"
#include "plant_sim/maglev_rig.hpp"

namespace ambid::diag {

ReplayInputs maglev_replay_inputs(const Experiment& measured, const std::vector<sim::Effect>& effects,
                                  Eigen::Index samples) {
  const std::size_t outputs = measured.controller ? measured.controller->outputs.size() : 0;
  ReplayInputs out{{}, Eigen::MatrixXd::Zero(samples, Eigen::Index(outputs))};
  for (const sim::Effect& e : effects) {
    if (e.name != "actuator_quantisation") {
      out.plant_effects.push_back(e);
      continue;
    }
    const auto& names = measured.controller->outputs;
    const auto output = std::find(names.begin(), names.end(), "u");
    const auto signal = std::find(measured.u_names.begin(), measured.u_names.end(), "u");
    if (output == names.end() || signal == measured.u_names.end() || measured.u.rows() < samples)
      throw Error("audit: actuator_quantisation needs the logged command u, driven by the controller");
    const Eigen::Index j = output - names.begin(), c = signal - measured.u_names.begin();
    const double step = e.at("step");
    for (Eigen::Index k = 0; k < samples; ++k)
      out.input_offset(k, j) = sim::round_to(measured.u(k, c), step) - measured.u(k, c);
  }
  return out;
}

}  // namespace ambid::diag
