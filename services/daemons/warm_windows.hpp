#pragma once
// The windows of one plant identified one after the other with a window method (every method
// but rpem), as the identifier daemon runs them. `pem` starts each window from the previous
// window's fit of the same plant description (IdentifyOptions::pem_warm_start: its v, offsets
// and predictor gain) instead of refining the closed-loop, deadbeat-iv, deadbeat and nominal
// starts from cold: on the deployed bearing's 0.5 s windows a cold fit runs into its iteration
// limit (2 x 60 steps, ~0.6 s of CPU), which at 10x real time left the identifier ~25 times
// too slow and 96 % of the history lost to alerted sample gaps (soak_slow_test.cpp). A warm
// fit that fails (its predictor diverges on the window, a refused residual check) is tried
// again cold; a window of another description (another loop or bearing) starts cold.
#include <cstdint>
#include <optional>
#include <string>

#include "core/experiment.hpp"
#include "identifier/identify_window.hpp"
#include "identifier/pem_warm_start.hpp"
#include "services/bus/messages.hpp"

namespace ambid::daemons {

class WarmWindows {
 public:
  explicit WarmWindows(ident::IdentifyOptions options) : options_(std::move(options)) {}

  // identify_window (identify_window.hpp) of `window`, read with the description
  // `description_id`. Throws what the cold fit throws.
  bus::IdentifiedModel identify(const Experiment& window, const std::string& description_id,
                                const std::string& plant_id, std::uint64_t seq);
  // Windows of this run that were fitted from the previous one's fit (for the logs and tests).
  std::uint64_t warm_fits() const { return warm_fits_; }

 private:
  ident::IdentifyOptions options_;
  std::optional<ident::PemWarmStart> start_;
  std::string start_description_;  // the description of the window start_ comes from
  std::uint64_t warm_fits_ = 0;
};

}  // namespace ambid::daemons
