#pragma once
// The plant families the identifier knows, in one place (experiment-format.md, "Plant
// families"): each brings the signals and order of its physical structure, the map from a
// realisation to its structure parameters and physical quantities, and the family-bound
// methods it offers (methods.hpp). The methods that need no structure (okid, closed-loop,
// projection) run on any plant model; a family-bound method on another model is refused with
// the families that offer it.
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/experiment.hpp"
#include "core/model_file.hpp"
#include "core/state_space.hpp"

namespace ambid::ident {

struct IdentifyOptions;
struct FrfStructure;

struct IdentificationFamily {
  std::string name;
  std::vector<std::string> y_names, u_names;  // the structure's signals, in its order
  Eigen::Index order = 0;                     // states of the physical structure (the default order)
  // Physical coordinates, structure parameters and physical quantities of a realisation of
  // `order` states; null when the family has none (the model stays in realisation coordinates).
  void (*add_structure)(const Experiment& experiment, const DiscreteSystem& realization, Model& model) = nullptr;
  // The family's grey-box fit of its physical parameters (method greybox); null: none.
  void (*greybox)(const Experiment& experiment, const IdentifyOptions& options, Model& model) = nullptr;
  std::vector<std::string> methods;  // the family-bound methods it offers
  // Its family-bound methods fit the plant's own equations on the u the plant got (no
  // controller, no r): a sample where a controller clamp acted is no less valid there, so they
  // keep every sample (identify_experiment.hpp) instead of the longest stretch without a clamp.
  bool keeps_clamped = false;
  // Its linear structure for the structured fit of `ambid frf` (frequency_domain/
  // frf_structured.hpp: the parameters and the unstable pole with sigmas); null: none.
  const FrfStructure& (*frf_structure)() = nullptr;
};

const std::vector<IdentificationFamily>& identification_families();
// "amb1dof_voltage, maglev1coil_voltage, lamstf".
std::string identification_family_names();
// The family called `model`, or null for a model the identifier has no structure for.
const IdentificationFamily* find_identification_family(const std::string& model);
// The families that offer `method`, in registry order.
std::vector<std::string> families_offering(const std::string& method);

}  // namespace ambid::ident
