#pragma once
// The identifier daemon's continuous mode (config "method": "rpem"): instead of identifying each
// window afresh, every window's samples go on into one recursive estimator
// (identifier/recursive_identification.hpp: the recursive prediction-error method, updated
// sample by sample) and its estimate at the window's end is published. The window is the
// publish period, 1 / publish_rate s. A window that does not follow the last one (samples
// dropped in between) restarts the predictor's state; another plant model restarts everything.
#include <cstdint>
#include <string>

#include "core/experiment.hpp"
#include "identifier/recursive_identification.hpp"
#include "services/bus/messages.hpp"

namespace ambid::daemons {

class ContinuousEstimator {
 public:
  explicit ContinuousEstimator(ident::RecursiveIdentifyOptions options = {});

  // The window's samples into the estimator, then its estimate as a message (time: the window's
  // last sample). Throws Error (InsufficientData before the estimator can start) naming what
  // the window lacks; the estimator keeps what it had.
  bus::IdentifiedModel identify(const Experiment& window, const std::string& plant_id, std::uint64_t seq);

 private:
  ident::RecursiveIdentification estimator_;
};

}  // namespace ambid::daemons
