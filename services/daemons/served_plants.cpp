#include "services/daemons/served_plants.hpp"

#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "services/bus/messages.hpp"

namespace ambid::daemons {

ServedPlants::ServedPlants(const nlohmann::json& config, const std::string& default_plant, const std::string& where) {
  const auto it = config.find("plants");
  if (it == config.end()) {
    single_ = true;
    listed_.insert(default_plant);
    return;
  }
  if (it->is_string() && it->get<std::string>() == "all") {
    all_ = true;
    return;
  }
  if (!it->is_array() || it->empty())
    throw Error(where + ": plants must be \"all\" or a non-empty list of plant ids, got " + it->dump());
  for (const nlohmann::json& id : *it) {
    if (!id.is_string() || id.get<std::string>().empty() || id.get<std::string>().size() > bus::limits::id_length)
      throw Error(where + ": plants: not a plant id (a string of 1 to " + std::to_string(bus::limits::id_length) +
                  " characters): " + id.dump());
    if (!listed_.insert(id.get<std::string>()).second)
      throw Error(where + ": plants: '" + id.get<std::string>() + "' listed twice");
  }
}

std::string ServedPlants::describe() const {
  if (all_) return "every plant id on the bus";
  std::string s = "plant" + std::string(listed_.size() > 1 ? "s " : " ");
  for (const std::string& id : listed_) s += (id == *listed_.begin() ? "" : ", ") + id;
  return s;
}

}  // namespace ambid::daemons
