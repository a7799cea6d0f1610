#include "services/daemons/continuous_estimator.hpp"

#include "services/convert/identified_model.hpp"

namespace ambid::daemons {

ContinuousEstimator::ContinuousEstimator(ident::RecursiveIdentifyOptions options) : estimator_(options) {}

bus::IdentifiedModel ContinuousEstimator::identify(const Experiment& window, const std::string& plant_id,
                                                   std::uint64_t seq) {
  estimator_.add(window);
  return convert::to_message(estimator_.estimate(), window, plant_id, seq, "rpem");
}

}  // namespace ambid::daemons
