#pragma once
// What diagnostics has per plant family (the families themselves: plant_sim/families.hpp):
// fault signatures and the monitored physical parameters (fault_signatures.hpp, diagnose) and
// the effect catalogue the audit fits (plant_sim's, where the family has one). Callers ask here
// and get a clear error naming the family and the piece it lacks; an unknown plant model is
// refused with the list of known ones.
#include <string>
#include <vector>

#include "core/experiment.hpp"
#include "plant_sim/effects.hpp"

namespace ambid::diag {

enum class DiagnosticsPiece {
  fault_signatures,  // closed-loop fault signatures and monitored parameters (monitor/)
  effect_catalogue,  // the audit's candidate extensions (audit/)
};

// Throws Error "WHO: unknown plant 'NAME' (known: ...)" or "WHO: plant model 'NAME' has no
// PIECE yet" unless the family has the piece.
void require_diagnostics_piece(const std::string& model, DiagnosticsPiece piece, const std::string& who);

// The family's effect catalogue, with the errors of require_diagnostics_piece.
const std::vector<sim::EffectSpec>& effect_catalogue_of(const std::string& model, const std::string& who);

// Starting values of the audit's candidates that the family reads from the record itself
// (maglev1coil_voltage: its grey-box fit, audit/maglev_starts.hpp); empty for a family without.
std::vector<sim::Effect> audit_starts_from_data(const Experiment& measured);

}  // namespace ambid::diag
