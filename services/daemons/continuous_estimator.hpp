#pragma once
// The identifier daemon's continuous mode (config "method": "rpem", the default): instead of
// identifying each window afresh, every window's samples go on into one recursive estimator
// (identifier/recursive_identification.hpp: the recursive prediction-error method, updated
// sample by sample) and its estimate at the window's end is published. The window is the
// publish period, 1 / publish_rate s. A window that does not follow the last one (samples
// dropped in between, a record's settling) restarts the predictor's state; another plant model
// restarts everything.
//
// After each published estimate the information carried to the next is scaled by `carry`
// (RecursiveIdentification::relax): each estimate then rests mostly on its own window, so
// successive estimates are nearly independent and the reported sigma is their scatter from
// window to window, as the diagnostics' detectors assume (measured:
// tests/daemons/continuous_statistics_slow_test.cpp). carry 1 publishes the plain recursive
// estimate, whose successive values share most of their samples (a 1 s memory published every
// 0.5 s) and scatter far less from window to window than their sigma says. That default is
// biased by about one window sigma (R1 +1.1..+1.5 % at 1 V); recursive.window_estimates
// (opt-in: RecursiveIdentification::begin_window) publishes each window's own estimate about a
// held theta instead, unbiased on a nominal bearing (tests/daemons/continuous_drift_slow_test.cpp)
// but not yet through a step fault (amb1dof_recursive_pem.hpp, begin_window).
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
  ident::RecursiveIdentifyOptions recursive{.forgetting = 0.9999, .offset_random_walk = 1e-6};
  double carry = 0.1;  // (0, 1]
};

class ContinuousEstimator {
 public:
  // Throws Error for forgetting or carry outside (0, 1].
  explicit ContinuousEstimator(ContinuousSettings settings = {});

  // The window's samples into the estimator, then its estimate as a message (time: the window's
  // last sample), then the relaxation by carry (begin_window with window_estimates). Throws Error (InsufficientData
  // before the estimator can start) naming what the window lacks; the estimator keeps what it had.
  bus::IdentifiedModel identify(const Experiment& window, const std::string& plant_id, std::uint64_t seq);

 private:
  double carry_;
  bool window_estimates_;
  ident::RecursiveIdentification estimator_;
};

}  // namespace ambid::daemons
