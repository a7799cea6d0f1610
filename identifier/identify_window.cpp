#include "identifier/identify_window.hpp"

#include "core/no_continuous_equivalent.hpp"

namespace ambid::ident {

IdentifyOptions window_identify_options(const std::string& method, Eigen::Index skip_samples) {
  identification_method(method, "identify window");
  if (skip_samples < 0)
    throw Error("identify window: skipped samples must be >= 0, got " + std::to_string(skip_samples));
  IdentifyOptions o;
  o.method = method;
  o.skip_samples = skip_samples;
  o.validation_fraction = 0.0;  // every sample of a window goes into its estimate
  o.jackknife_segments = 0;
  return o;
}

std::vector<Estimate> with_uncertainty(const std::map<std::string, double>& values,
                                       const std::map<std::string, double>& sigmas, const std::string& who) {
  std::vector<Estimate> out;
  for (const auto& [name, value] : values) {
    if (sigmas.empty()) {  // a method without sigmas: diagnostics uses the baseline's scatter
      out.push_back({name, value, 0.0});
      continue;
    }
    const auto sigma = sigmas.find(name);
    if (sigma == sigmas.end()) throw Error(who + ": no uncertainty of " + name);
    out.push_back({name, value, sigma->second});
  }
  return out;
}

WindowIdentification identify_window(const Experiment& window, const IdentifyOptions& options) {
  WindowIdentification out;
  out.model = identify_experiment(window, options);
  if (!out.model.no_continuous.empty())
    throw NoContinuousEquivalent("no continuous-time model, so no physical parameters: " + out.model.no_continuous);
  out.parameters = with_uncertainty(out.model.parameters, out.model.uncertainty, "identify window");
  out.physical = with_uncertainty(out.model.physical, out.model.uncertainty, "identify window");
  return out;
}

const std::vector<std::string>& window_failure_reasons() {
  static const std::vector<std::string> reasons{"no_continuous_model", "insufficient_data", "error"};
  return reasons;
}

WindowFailure window_failure(const Error& error) {
  const std::vector<std::string>& r = window_failure_reasons();
  if (dynamic_cast<const NoContinuousEquivalent*>(&error)) return {r[0], error.what()};
  if (dynamic_cast<const InsufficientData*>(&error)) return {r[1], error.what()};
  return {r[2], error.what()};
}

}  // namespace ambid::ident
