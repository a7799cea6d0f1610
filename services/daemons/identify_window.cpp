#include "services/daemons/identify_window.hpp"

#include "core/error.hpp"
#include "services/convert/identified_model.hpp"

namespace ambid::daemons {

bus::IdentifiedModel identify_window(const Experiment& window, const std::string& plant_id, std::uint64_t seq,
                                     const ident::IdentifyOptions& options) {
  return convert::to_message(ident::identify_window(window, options), window, plant_id, seq, options.method);
}

bus::IdentifiedModel WindowIdentifier::identify(const Experiment& window, const std::string& plant_id,
                                                std::uint64_t seq) {
  if (options_.method != "pem") return identify_window(window, plant_id, seq, options_);
  ident::IdentifyOptions o = options_;
  o.pem_warm_start = warm_;
  ident::WindowIdentification result;
  try {
    result = ident::identify_window(window, o);
  } catch (const Error&) {
    if (!warm_) throw;
    warm_.reset();  // the plant moved too far from the last fit (or that fit misled): start cold
    o.pem_warm_start.reset();
    result = ident::identify_window(window, o);
  }
  warm_ = ident::pem_warm_start(result.model);
  return convert::to_message(result, window, plant_id, seq, o.method);
}

}  // namespace ambid::daemons
