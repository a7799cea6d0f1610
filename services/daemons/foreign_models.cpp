#include "services/daemons/foreign_models.hpp"

#include <algorithm>

namespace ambid::daemons {

void ForeignModels::published(const bus::IdentifiedModel& m) {
  std::deque<Own>& own = own_[m.plant_id];
  own.push_back({m.seq, m.time});
  if (own.size() > remembered_) own.pop_front();
}

bool ForeignModels::foreign(const bus::IdentifiedModel& m) {
  std::deque<Own>& own = own_[m.plant_id];
  const auto it =
      std::find_if(own.begin(), own.end(), [&](const Own& o) { return o.seq == m.seq && o.time == m.time; });
  if (it == own.end() || it->echoed) return true;
  it->echoed = true;
  return false;
}

}  // namespace ambid::daemons
