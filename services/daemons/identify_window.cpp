#include "services/daemons/identify_window.hpp"

#include "services/convert/identified_model.hpp"

namespace ambid::daemons {

bus::IdentifiedModel identify_window(const Experiment& window, const std::string& plant_id, std::uint64_t seq,
                                     const ident::IdentifyOptions& options) {
  return convert::to_message(ident::identify_window(window, options), window, plant_id, seq, options.method);
}

}  // namespace ambid::daemons
