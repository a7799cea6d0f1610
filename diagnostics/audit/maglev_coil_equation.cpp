#include "diagnostics/audit/maglev_coil_equation.hpp"

#include <algorithm>
#include <memory>
#include <string>

#include "core/error.hpp"
#include "plant_sim/families.hpp"
#include "plant_sim/maglev_extended.hpp"

namespace ambid::diag {
namespace {

Eigen::Index maglev_coil_signal(const std::vector<std::string>& names, const char* name) {
  const auto it = std::find(names.begin(), names.end(), name);
  if (it == names.end())
    throw Error(std::string("audit: the coil equation needs the logged signal '") + name + "' of maglev1coil_voltage");
  return Eigen::Index(it - names.begin());
}

}  // namespace

OneStepPrediction maglev_coil_prediction(const Experiment& measured, const std::vector<sim::Effect>& effects) {
  const Eigen::Index ii = maglev_coil_signal(measured.y_names, "i"), iu = maglev_coil_signal(measured.u_names, "u");
  const std::unique_ptr<sim::Plant> plant =
      sim::plant_family(measured.plant.model, "audit").make_extended_plant(measured, effects);
  const auto* maglev = dynamic_cast<const sim::MaglevExtended*>(plant.get());
  if (!maglev) throw Error("audit: the coil equation is defined for maglev1coil_voltage only");
  const double dt = measured.sample_time, i0 = measured.operating_value("i");
  const Eigen::Index N = measured.samples();
  OneStepPrediction out{Eigen::MatrixXd(N, 1), Eigen::MatrixXd(N, 1)};
  for (Eigen::Index k = 0; k + 1 < N; ++k) {
    out.measured(k, 0) = measured.y(k + 1, ii) - i0;
    out.predicted(k, 0) = maglev->coil_current_after(measured.y(k, ii), measured.u(k, iu), dt) - i0;
  }
  out.measured(N - 1, 0) = out.predicted(N - 1, 0) = measured.y(N - 1, ii) - i0;
  return out;
}

}  // namespace ambid::diag
