#include "identifier/families/amb1dof_realization.hpp"

#include <nlohmann/json.hpp>

#include "identifier/amb1dof_structure.hpp"

namespace ambid::ident {

void add_amb1dof_structure(const Experiment& e, const DiscreteSystem& realization, Model& model) {
  const Amb1dofPhysicalModel phys = amb1dof_physical_model(realization);
  model.discrete = phys.discrete;
  model.continuous = phys.continuous;
  const Amb1dofNominal nominal = amb1dof_nominal(e, "identify");
  const Eigen::Matrix<double, 9, 1> v = amb1dof_structure_vector(phys.continuous);
  const Eigen::Matrix<double, 9, 1> scale = amb1dof_physical_scale(nominal.L1, nominal.L2, nominal.m);
  for (Eigen::Index i = 0; i < 9; ++i) {
    model.parameters[amb1dof_structure_names()[std::size_t(i)]] = v(i);
    model.physical[amb1dof_physical_names()[std::size_t(i)]] = v(i) * scale(i);
  }
  model.extra.json()["structure_deviation"] = amb1dof_structure_deviation(phys.continuous);
}

}  // namespace ambid::ident
