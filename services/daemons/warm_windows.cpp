#include "services/daemons/warm_windows.hpp"

#include "services/convert/identified_model.hpp"

namespace ambid::daemons {

bus::IdentifiedModel WarmWindows::identify(const Experiment& window, const std::string& description_id,
                                           const std::string& plant_id, std::uint64_t seq) {
  const bool warm = options_.method == "pem" && start_ && start_description_ == description_id;
  std::optional<ident::WindowIdentification> fit;
  if (warm) {
    ident::IdentifyOptions o = options_;
    o.pem_warm_start = start_;
    try {
      fit = ident::identify_window(window, o);
      ++warm_fits_;
    } catch (const Error&) {
      // Tried again from the cold starts below; their failure is the window's.
    }
  }
  if (!fit) fit = ident::identify_window(window, options_);
  if (options_.method == "pem") {
    start_ = ident::pem_warm_start(fit->model);
    start_description_ = description_id;
  }
  return convert::to_message(*fit, window, plant_id, seq, options_.method);
}

}  // namespace ambid::daemons
