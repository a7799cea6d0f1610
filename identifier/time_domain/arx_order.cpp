#include "identifier/time_domain/arx_order.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.hpp"

namespace ambid::ident {

Eigen::Index default_arx_order(Eigen::Index samples, Eigen::Index outputs, Eigen::Index inputs) {
  if (outputs < 1 || inputs < 0)
    throw Error("ARX order: needs at least one output and no negative input count, got " + std::to_string(outputs) +
                " outputs and " + std::to_string(inputs) + " inputs");
  const Eigen::Index per_lag = outputs + inputs;
  const Eigen::Index most = samples / (kArxRowsPerParameter * per_lag);
  if (most < 1)
    throw InsufficientData(
        "ARX order: an order-1 ARX model (" + std::to_string(per_lag) + " coefficients per lag) needs more than " +
        std::to_string(kArxRowsPerParameter * per_lag - 1) + " samples (" + std::to_string(kArxRowsPerParameter) +
        " equations per coefficient), got " + std::to_string(samples));
  const auto grown = static_cast<Eigen::Index>(std::ceil(kArxOrderPerLogSample * std::log(double(samples))));
  return std::min(grown, most);
}

const std::vector<Eigen::Index>& default_markov_counts() {
  static const std::vector<Eigen::Index> counts = {30, 60, 100};
  return counts;
}

}  // namespace ambid::ident
