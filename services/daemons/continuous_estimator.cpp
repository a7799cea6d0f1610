#include "services/daemons/continuous_estimator.hpp"

#include "core/error.hpp"
#include "services/convert/identified_model.hpp"

namespace ambid::daemons {

ContinuousEstimator::ContinuousEstimator(ContinuousSettings settings)
    : carry_(settings.carry), estimator_(settings.recursive) {
  if (!(carry_ > 0.0 && carry_ <= 1.0))
    throw Error("continuous estimator: carry must be in (0, 1], got " + std::to_string(carry_));
  if (!settings.recursive.window_estimates)
    throw Error("continuous estimator: publishes per-window estimates (recursive.window_estimates must be true)");
}

bus::IdentifiedModel ContinuousEstimator::identify(const Experiment& window, const std::string& plant_id,
                                                   std::uint64_t seq) {
  estimator_.add(window);
  estimator_.end_window();
  bus::IdentifiedModel model = convert::to_message(estimator_.estimate(), window, plant_id, seq, "rpem");
  estimator_.begin_window(carry_);
  return model;
}

}  // namespace ambid::daemons
