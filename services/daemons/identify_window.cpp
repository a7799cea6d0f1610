#include "services/daemons/identify_window.hpp"

#include <algorithm>

#include "core/error.hpp"

namespace ambid::daemons {
namespace {

bus::Matrix to_message(const Eigen::MatrixXd& m) {
  bus::Matrix out;
  out.rows = std::uint32_t(m.rows());
  out.cols = std::uint32_t(m.cols());
  for (Eigen::Index i = 0; i < m.rows(); ++i)
    for (Eigen::Index j = 0; j < m.cols(); ++j) out.values.push_back(m(i, j));
  return out;
}

template <class System>
bus::StateSpace to_message(const System& s) {
  return {to_message(s.A), to_message(s.B), to_message(s.C), to_message(s.D)};
}

std::vector<bus::Estimate> estimates(const std::map<std::string, double>& values,
                                     const std::map<std::string, double>& sigmas) {
  std::vector<bus::Estimate> out;
  for (const auto& [name, value] : values) {
    if (sigmas.empty()) {  // a method without sigmas: diagnostics uses the baseline's scatter
      out.push_back({name, value, 0.0});
      continue;
    }
    const auto sigma = sigmas.find(name);
    if (sigma == sigmas.end()) throw Error("identifier: the method reported no uncertainty of " + name);
    out.push_back({name, value, sigma->second});
  }
  return out;
}

}  // namespace

ident::IdentifyOptions window_identify_options(const std::string& method, Eigen::Index skip_samples) {
  const auto& methods = ident::identification_methods();
  if (std::find(methods.begin(), methods.end(), method) == methods.end()) {
    std::string known;
    for (const auto& m : methods) known += (known.empty() ? "" : ", ") + m;
    throw Error("identifier: unknown method '" + method + "' (expected one of " + known + ")");
  }
  if (skip_samples < 0) throw Error("identifier: skipped samples must be >= 0, got " + std::to_string(skip_samples));
  ident::IdentifyOptions o;
  o.method = method;
  o.skip_samples = skip_samples;
  o.validation_fraction = 0.0;  // every sample of a window goes into its estimate
  // No jackknife: diagnostics learns each parameter's window-to-window scatter (baseline.hpp),
  // and 8 leave-one-out fits per window would cost the stack its real-time headroom.
  o.jackknife_segments = 0;
  return o;
}

bus::IdentifiedModel identify_window(const Experiment& window, const std::string& plant_id, std::uint64_t seq,
                                     const ident::IdentifyOptions& options) {
  const Model id = ident::identify_experiment(window, options);
  bus::IdentifiedModel m;
  m.plant_id = plant_id;
  m.seq = seq;
  m.time = window.t(window.samples() - 1);
  m.window = double(window.samples()) * window.sample_time;
  m.plant_model = window.plant.model;
  m.method = options.method;
  m.sample_time = window.sample_time;
  m.discrete = to_message(id.discrete);
  if (id.continuous) m.continuous = to_message(*id.continuous);
  m.parameters = estimates(id.parameters, id.uncertainty);
  m.physical = estimates(id.physical, id.uncertainty);
  for (const auto& [output, nrmse] : id.fit_nrmse) m.nrmse.push_back({output, nrmse});
  return m;
}

}  // namespace ambid::daemons
