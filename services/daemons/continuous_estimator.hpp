#pragma once
// The identifier daemon's continuous mode (config "method": "rpem", the default): instead of
// identifying each window afresh, every window's samples go on into one recursive estimator
// (identifier/recursive_identification.hpp: the recursive prediction-error method, updated
// sample by sample) and its estimate at the window's end is published. The window is the
// publish period, 1 / publish_rate s. A window that does not follow the last one (samples
// dropped in between, a record's settling) restarts the predictor's state; another plant model
// restarts everything.
//
// Each published estimate is its window's own (RecursiveIdentification::begin_window,
// end_window: a Gauss-Newton step about a held theta, the long-memory estimate with its
// information scaled by `carry` as the prior), so successive estimates are nearly independent
// and the reported sigma is their scatter from window to window, as the diagnostics' detectors
// assume (tests/daemons/continuous_statistics_slow_test.cpp), and they are unbiased on a
// nominal bearing (tests/daemons/continuous_drift_slow_test.cpp). A window far from its prior
// (a step fault, a swapped plant) or after a gap is published from a plain RPEM run beside it,
// and the next window is held at that estimate (tests/daemons/continuous_step_fault_test.cpp).
#include <cstdint>
#include <string>

#include "core/experiment.hpp"
#include "identifier/recursive_identification.hpp"
#include "services/bus/messages.hpp"

namespace ambid::daemons {

struct ContinuousSettings {
  // Offsets: the operating point moves slowly (temperature) and with a fault; each window's
  // prior lets them re-settle, so their random walk can be slow (1e-4, the family's default for
  // a plain recursive run, let them absorb part of the noise that R1, R2 should see and made
  // those noisier).
  ident::RecursiveIdentifyOptions recursive{.forgetting = 0.9999, .offset_random_walk = 1e-6, .window_estimates = true};
  double carry = 0.1;  // (0, 1]
};

class ContinuousEstimator {
 public:
  // Throws Error for forgetting or carry outside (0, 1] or without recursive.window_estimates.
  explicit ContinuousEstimator(ContinuousSettings settings = {});

  // The window's samples into the estimator, then its estimate as a message (time: the window's
  // last sample), then the next window begun with carry. Throws Error (InsufficientData before
  // the estimator can start) naming what the window lacks; the estimator keeps what it had.
  bus::IdentifiedModel identify(const Experiment& window, const std::string& plant_id, std::uint64_t seq);

 private:
  double carry_;
  ident::RecursiveIdentification estimator_;
};

}  // namespace ambid::daemons
