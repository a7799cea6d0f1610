#include "services/daemons/identify_window.hpp"

#include "identifier/amb1dof_deadbeat.hpp"

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
  for (const auto& [name, value] : values) out.push_back({name, value, sigmas.at(name)});
  return out;
}

}  // namespace

bus::IdentifiedModel identify_window(const Experiment& window, const std::string& plant_id, std::uint64_t seq,
                                     const ident::DeadbeatOptions& options) {
  const ident::Amb1dofIdentification id = ident::identify_amb1dof_deadbeat(window, options);
  bus::IdentifiedModel m;
  m.plant_id = plant_id;
  m.seq = seq;
  m.time = window.t(window.samples() - 1);
  m.window = double(window.samples()) * window.sample_time;
  m.plant_model = window.plant.model;
  m.method = kDeadbeatMethod;
  m.sample_time = window.sample_time;
  m.discrete = to_message(id.realization.system);
  m.continuous = to_message(id.continuous);
  m.parameters = estimates(id.parameters, id.parameter_uncertainty);
  m.physical = estimates(id.physical, id.physical_uncertainty);
  return m;
}

}  // namespace ambid::daemons
