#include "services/daemons/model_gaps.hpp"

namespace ambid::daemons {

std::uint64_t ModelGaps::missed(std::uint64_t seq) {
  const std::uint64_t gap = last_ && seq > *last_ + 1 ? seq - *last_ - 1 : 0;
  restarted_ = last_ && seq <= *last_;
  last_ = seq;
  return gap;
}

}  // namespace ambid::daemons
