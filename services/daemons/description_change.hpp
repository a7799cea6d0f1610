#pragma once
// What a new plant description means for the diagnostics of its plant (services/daemons/
// README.md, "Swapping sources"). Physical parameters belong to the bearing, not to its loop:
//   same        the same description: nothing changes
//   first       the first description this daemon sees for the plant: its fault signatures
//   controller  the same bearing (model and nominal parameters) in another loop (controller,
//               signals, operating point or sample time): baselines and trends go on; the
//               fault-isolation signatures are recomputed for the new loop
//   bearing     another bearing (model or nominal parameters differ): a new baseline
#include <string>

#include "services/bus/messages.hpp"

namespace ambid::daemons {

enum class DescriptionChange { same, first, controller, bearing };

// `previous`: the description in force (null before the first).
DescriptionChange classify(const bus::PlantDescription* previous, const bus::PlantDescription& next);

// "R1 17.5 -> 21, R2 ..." (model first when it differs): what makes `next` another bearing.
std::string bearing_difference(const bus::PlantDescription& previous, const bus::PlantDescription& next);

}  // namespace ambid::daemons
