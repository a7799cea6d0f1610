#include "services/convert/identified_model.hpp"

#include <vector>

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

std::vector<bus::Estimate> to_message(const std::vector<ident::Estimate>& estimates) {
  std::vector<bus::Estimate> out;
  for (const ident::Estimate& e : estimates) out.push_back({e.name, e.value, e.sigma});
  return out;
}

}  // namespace

bus::IdentifiedModel to_message(const ident::WindowIdentification& identified, const Experiment& window,
                                const std::string& plant_id, std::uint64_t seq, const std::string& method) {
  const Model& id = identified.model;
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
  m.parameters = to_message(identified.parameters);
  m.physical = to_message(identified.physical);
  for (const auto& [output, nrmse] : id.fit_nrmse) m.nrmse.push_back({output, nrmse});
  return m;
}

}  // namespace ambid::convert
