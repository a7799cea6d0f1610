#pragma once
// Which plant ids one identifier or diagnostics daemon serves (config key "plants"):
//   absent        the one plant of --plant-id (a daemon per plant, as before)
//   ["a", "b"]    exactly these (a fleet divided between processes by configuration lists)
//   "all"         every plant id seen on the bus (one process for the whole fleet)
// Several identifier processes share a fleet by disjoint lists; a plant id served twice is
// detected at run time (foreign_models.hpp) and reported, never silently doubled.
#include <set>
#include <string>

#include <nlohmann/json_fwd.hpp>

namespace ambid::daemons {

class ServedPlants {
 public:
  // Throws Error naming the value for anything but a non-empty list of distinct non-empty ids
  // or "all". `where`: "identifier config", ...
  ServedPlants(const nlohmann::json& config, const std::string& default_plant, const std::string& where);

  bool serves(const std::string& plant_id) const { return all_ || listed_.count(plant_id) > 0; }
  bool all() const { return all_; }
  const std::set<std::string>& listed() const { return listed_; }  // empty for "all"
  // True when the config named no list (the single plant of --plant-id).
  bool single() const { return single_; }
  std::string describe() const;  // "plants a, b" or "every plant id on the bus"

 private:
  bool all_ = false, single_ = false;
  std::set<std::string> listed_;
};

}  // namespace ambid::daemons
