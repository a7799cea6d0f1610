#include "diagnostics/plant_families.hpp"

#include <algorithm>
#include <vector>

#include "core/error.hpp"
#include "diagnostics/audit/maglev_coil_equation.hpp"
#include "diagnostics/audit/maglev_dac_replay.hpp"
#include "diagnostics/audit/maglev_starts.hpp"
#include "diagnostics/maglev_fault_signatures.hpp"
#include "identifier/identify_window.hpp"
#include "plant_sim/families.hpp"

namespace ambid::diag {
namespace {

// The families whose parameters diagnostics monitors (one place: adding a family adds a row).
const std::vector<MonitoredFamily>& monitored_families() {
  static const std::vector<MonitoredFamily> families = {
      {"amb1dof_voltage", amb1dof_monitored_parameters, closed_loop_fault_hypotheses, default_fault_hypotheses,
       ident::kDefaultWindowMethod, 0.25, 1000},
      // Records of a few thousand samples at 1.3-4 ms with reference steps every 1.5-2 s: a
      // window of 3 s holds one or two steps (the grey-box fit needs a change of level for n_x).
      {"maglev1coil_voltage", maglev_monitored_parameters, maglev_fault_hypotheses, default_maglev_fault_hypotheses,
       "greybox", 3.0, 0},
  };
  return families;
}

const MonitoredFamily* find_monitored(std::string_view model) {
  const auto& families = monitored_families();
  const auto it = std::find_if(families.begin(), families.end(), [&](const auto& f) { return f.name == model; });
  return it == families.end() ? nullptr : &*it;
}

// The families whose audit reads starting values, inputs of the replay, or one-step
// predictions from the record.
struct AuditFromData {
  const char* family;
  std::vector<sim::Effect> (*starts)(const Experiment&);
  ReplayInputs (*replay_inputs)(const Experiment&, const std::vector<sim::Effect>&, Eigen::Index);
  OneStepPrediction (*one_step)(const Experiment&, const std::vector<sim::Effect>&);
};
constexpr AuditFromData kAuditFromData[] = {
    {"maglev1coil_voltage", maglev_audit_starts, maglev_replay_inputs, maglev_coil_prediction}};

}  // namespace

void require_diagnostics_piece(const std::string& model, DiagnosticsPiece piece, const std::string& who) {
  const sim::PlantFamily& family = sim::plant_family(model, who);
  if (piece == DiagnosticsPiece::effect_catalogue && (!family.effect_catalogue || !family.make_extended_plant))
    sim::family_lacks(family, "effect catalogue", who);
  if (piece == DiagnosticsPiece::fault_signatures && !find_monitored(model))
    sim::family_lacks(family, "fault signatures (nor monitored parameters)", who);
}

const MonitoredFamily& monitored_family(const std::string& model, const std::string& who) {
  require_diagnostics_piece(model, DiagnosticsPiece::fault_signatures, who);
  return *find_monitored(model);
}

std::vector<std::string> monitored_parameters(const std::string& family) {
  std::vector<std::string> out;
  for (const MonitoredParameter& p : monitored_family(family, "diagnostics").monitored()) out.emplace_back(p.parameter);
  return out;
}

ParameterRole parameter_role(const std::string& family, std::string_view parameter) {
  const auto monitored = monitored_family(family, "diagnostics").monitored();
  for (const MonitoredParameter& p : monitored)
    if (p.parameter == parameter) return p.role;
  std::string names;
  for (const MonitoredParameter& p : monitored) names += (names.empty() ? "" : ", ") + std::string(p.parameter);
  throw Error("diagnostics: parameter '" + std::string(parameter) + "' is not monitored for " + family +
              " (monitored: " + names + ")");
}

std::vector<FaultHypothesis> fault_hypotheses(const Experiment& header, const SignatureOptions& options) {
  return monitored_family(header.plant.model, "fault signatures").hypotheses(header, options);
}

const std::vector<FaultHypothesis>& default_fault_hypotheses(const std::string& family) {
  return monitored_family(family, "fault signatures").default_hypotheses();
}

const std::vector<sim::EffectSpec>& effect_catalogue_of(const std::string& model, const std::string& who) {
  require_diagnostics_piece(model, DiagnosticsPiece::effect_catalogue, who);
  return sim::plant_family(model, who).effect_catalogue();
}

std::vector<sim::Effect> audit_starts_from_data(const Experiment& measured) {
  for (const auto& d : kAuditFromData)
    if (measured.plant.model == d.family) return d.starts(measured);
  return {};
}

ReplayInputs audit_replay_inputs(const Experiment& measured, const std::vector<sim::Effect>& effects,
                                 Eigen::Index samples) {
  for (const auto& d : kAuditFromData)
    if (measured.plant.model == d.family) return d.replay_inputs(measured, effects, samples);
  const Eigen::Index outputs = measured.controller ? Eigen::Index(measured.controller->outputs.size()) : 0;
  return {effects, Eigen::MatrixXd::Zero(samples, outputs)};
}

OneStepPrediction audit_one_step_prediction(const Experiment& measured, const std::vector<sim::Effect>& effects) {
  for (const auto& d : kAuditFromData)
    if (measured.plant.model == d.family) return d.one_step(measured, effects);
  return {};
}

}  // namespace ambid::diag
