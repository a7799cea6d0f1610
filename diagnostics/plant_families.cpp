#include "diagnostics/plant_families.hpp"

#include <algorithm>
#include <vector>

#include "diagnostics/audit/maglev_starts.hpp"
#include "plant_sim/families.hpp"

namespace ambid::diag {
namespace {

// The families whose fault signatures monitor/fault_signatures.cpp derives.
const std::vector<std::string>& families_with_fault_signatures() {
  static const std::vector<std::string> names = {"amb1dof_voltage"};
  return names;
}

// The families whose audit reads starting values from the record.
struct DataStarts {
  const char* family;
  std::vector<sim::Effect> (*starts)(const Experiment&);
};
constexpr DataStarts kDataStarts[] = {{"maglev1coil_voltage", maglev_audit_starts}};

}  // namespace

void require_diagnostics_piece(const std::string& model, DiagnosticsPiece piece, const std::string& who) {
  const sim::PlantFamily& family = sim::plant_family(model, who);
  if (piece == DiagnosticsPiece::effect_catalogue && (!family.effect_catalogue || !family.make_extended_plant))
    sim::family_lacks(family, "effect catalogue", who);
  const auto& signed_families = families_with_fault_signatures();
  if (piece == DiagnosticsPiece::fault_signatures &&
      std::find(signed_families.begin(), signed_families.end(), model) == signed_families.end())
    sim::family_lacks(family, "fault signatures (nor monitored parameters)", who);
}

const std::vector<sim::EffectSpec>& effect_catalogue_of(const std::string& model, const std::string& who) {
  require_diagnostics_piece(model, DiagnosticsPiece::effect_catalogue, who);
  return sim::plant_family(model, who).effect_catalogue();
}

std::vector<sim::Effect> audit_starts_from_data(const Experiment& measured) {
  for (const auto& d : kDataStarts)
    if (measured.plant.model == d.family) return d.starts(measured);
  return {};
}

}  // namespace ambid::diag
