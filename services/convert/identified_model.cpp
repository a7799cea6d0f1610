#include "services/convert/identified_model.hpp"

#include <algorithm>
#include <array>
#include <map>
#include <vector>

#include "core/error.hpp"

namespace ambid::convert {
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

bus::IdentifiedModel to_message(const Model& id, const Experiment& window, const std::string& plant_id,
                                std::uint64_t seq, const std::string& method) {
  bus::IdentifiedModel m;
  m.plant_id = plant_id;
  m.seq = seq;
  m.time = window.t(window.samples() - 1);
  m.window = double(window.samples()) * window.sample_time;
  m.plant_model = window.plant.model;
  m.method = method;
  m.sample_time = window.sample_time;
  m.discrete = to_message(id.discrete);
  if (id.continuous) m.continuous = to_message(*id.continuous);
  m.parameters = estimates(id.parameters, id.uncertainty);
  m.physical = estimates(id.physical, id.uncertainty);
  for (const auto& [output, nrmse] : id.fit_nrmse) m.nrmse.push_back({output, nrmse});
  return m;
}

diag::EstimateWindow estimate_window(const bus::IdentifiedModel& model, diag::Source source) {
  static const std::array<std::string, 7> monitored{"R1", "R2", "kw1", "kw2", "kr1", "kr2", "ks"};
  diag::EstimateWindow w;
  w.time = model.time;
  w.plant_id = model.plant_id;
  w.source = source;
  for (const bus::Estimate& e : model.physical)
    if (std::find(monitored.begin(), monitored.end(), e.name) != monitored.end())
      w.estimates.push_back({e.name, e.value, e.sigma});
  return w;
}

}  // namespace ambid::convert
