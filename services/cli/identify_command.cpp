// `ambid identify`: identify the plant of an experiment by a named method and write model.json.
// A model without a continuous-time equivalent is still written (its discrete part, key
// no_continuous saying why) with a warning on stderr, and the exit status is 0.
#include <iostream>
#include <memory>

#include <nlohmann/json.hpp>

#include "core/experiment_io.hpp"
#include "core/model_file.hpp"
#include "identifier/identify_experiment.hpp"
#include "identifier/methods.hpp"
#include "services/cli/commands.hpp"

namespace ambid::cli {
namespace {

struct IdentifyArguments {
  std::string experiment;
  ident::IdentifyOptions options;
  std::string out;
};

void print_summary(const Model& m, const std::string& out) {
  std::cout << "ambid identify: " << m.plant_model << " by " << m.method << ", " << m.discrete.states() << " states\n";
  if (!m.no_continuous.empty())
    std::cout << "  discrete model only: no continuous-time equivalent (model.json key no_continuous, warning below)\n";
  for (const auto& [name, value] : m.parameters) {
    std::cout << "  " << name << " = " << value;
    if (const auto it = m.uncertainty.find(name); it != m.uncertainty.end()) std::cout << " +- " << it->second;
    std::cout << "\n";
  }
  for (const auto& [name, value] : m.fit_nrmse) std::cout << "  validation nrmse " << name << ": " << value << "\n";
  if (m.extra.json().contains("warnings"))
    for (const auto& w : m.extra.json()["warnings"])
      std::cerr << "ambid identify: warning: " << w.get<std::string>() << "\n";
  std::cout << "  wrote " << out << "\n";
}

}  // namespace

void add_identify_command(CLI::App& app) {
  auto args = std::make_shared<IdentifyArguments>();
  auto& o = args->options;
  CLI::App* cmd = app.add_subcommand("identify", "identify the plant of an experiment and write model.json");
  cmd->add_option("experiment", args->experiment, "experiment (.json sidecar, .csv or stem)")->required();
  cmd->add_option("--method", o.method, ident::method_names(" | ") + " (below)")->required();
  cmd->add_option("--order", o.order, "model states (0: the plant model's, else ERA's suggestion)")
      ->capture_default_str();
  cmd->add_option("--arx-order", o.arx_order, "ARX order of okid/closed-loop/projection (0: default)")
      ->capture_default_str();
  cmd->add_option("--instrument-lags", o.instrument_lags, "deadbeat-iv: instruments r[k..k-N] (0: default)")
      ->capture_default_str();
  cmd->add_option("--jackknife", o.jackknife_segments,
                  "okid/closed-loop/projection: segments of the uncertainty jackknife (0: no uncertainty)")
      ->capture_default_str();
  cmd->add_option("--skip", o.skip_samples, "leading samples to drop (settling transient)")->capture_default_str();
  cmd->add_option("--validation", o.validation_fraction, "fraction at the end kept for validation")
      ->capture_default_str();
  cmd->add_option("--out", args->out, "model file to write")->required();
  cmd->footer("--method:\n" + ident::method_table());
  cmd->callback([args] {
    const ReadResult read = read_experiment(args->experiment);
    for (const auto& w : read.warnings) std::cerr << "ambid identify: warning: " << w << "\n";
    const Model model = ident::identify_experiment(read.experiment, args->options);
    write_model(model, args->out);
    print_summary(model, args->out);
    std::cout << "  clamped samples (a controller clamp acted, not exogenous): " << read.clamped_samples << " of "
              << read.experiment.samples()
              << (read.clamped_samples ? "; left out of the validation nrmse, and of the fit unless its method keeps "
                                         "them (model.json clamped_samples)"
                                       : "")
              << "\n";
  });
}

}  // namespace ambid::cli
