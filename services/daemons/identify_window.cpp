#include "services/daemons/identify_window.hpp"

#include <algorithm>

#include "core/error.hpp"
#include "services/convert/identified_model.hpp"

namespace ambid::daemons {

ident::IdentifyOptions window_identify_options(const std::string& method, Eigen::Index skip_samples) {
  const auto& methods = ident::identification_methods();
  if (std::find(methods.begin(), methods.end(), method) == methods.end()) {
    std::string known;
    for (const auto& m : methods) known += (known.empty() ? "" : ", ") + m;
    throw Error("identifier: unknown method '" + method + "' (expected one of " + known + ")");
  }
  if (skip_samples < 0) throw Error("identifier: skipped samples must be >= 0, got " + std::to_string(skip_samples));
  ident::IdentifyOptions o;
  o.method = method;
  o.skip_samples = skip_samples;
  o.validation_fraction = 0.0;  // every sample of a window goes into its estimate
  // No jackknife: diagnostics learns each parameter's window-to-window scatter (baseline.hpp),
  // and 8 leave-one-out fits per window would cost the stack its real-time headroom.
  o.jackknife_segments = 0;
  return o;
}

bus::IdentifiedModel identify_window(const Experiment& window, const std::string& plant_id, std::uint64_t seq,
                                     const ident::IdentifyOptions& options) {
  const Model id = ident::identify_experiment(window, options);
  return convert::to_message(id, window, plant_id, seq, options.method);
}

}  // namespace ambid::daemons
