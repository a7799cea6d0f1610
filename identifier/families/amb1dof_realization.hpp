#pragma once
// The amb1dof_voltage family's physical structure of a 4-state realisation with outputs
// [x, i1, i2] (plant_families.hpp): physical coordinates, v1..v9 and the physical quantities.
#include "core/experiment.hpp"
#include "core/model_file.hpp"
#include "core/state_space.hpp"

namespace ambid::ident {

// Fills model.discrete, continuous, parameters (v1..v9), physical and extra.structure_deviation.
// Error when the realisation cannot be brought to physical coordinates or the experiment lacks
// the nominal L1, L2, m.
void add_amb1dof_structure(const Experiment& experiment, const DiscreteSystem& realization, Model& model);

}  // namespace ambid::ident
