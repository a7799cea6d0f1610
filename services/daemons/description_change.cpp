#include "services/daemons/description_change.hpp"

#include <map>
#include <sstream>

namespace ambid::daemons {
namespace {

std::map<std::string, double> parameters(const bus::PlantDescription& d) {
  std::map<std::string, double> out;
  for (const auto& [name, value] : d.parameters) out[name] = value;
  return out;
}

std::string value_of(const std::map<std::string, double>& m, const std::string& name) {
  const auto it = m.find(name);
  if (it == m.end()) return "-";
  std::ostringstream s;
  s << it->second;
  return s.str();
}

}  // namespace

DescriptionChange classify(const bus::PlantDescription* previous, const bus::PlantDescription& next) {
  if (!previous) return DescriptionChange::first;
  if (previous->description_id == next.description_id) return DescriptionChange::same;
  if (previous->model != next.model || parameters(*previous) != parameters(next)) return DescriptionChange::bearing;
  return DescriptionChange::controller;
}

std::string bearing_difference(const bus::PlantDescription& previous, const bus::PlantDescription& next) {
  std::ostringstream s;
  if (previous.model != next.model) s << "model " << previous.model << " -> " << next.model;
  const auto before = parameters(previous), after = parameters(next);
  auto all = before;
  all.insert(after.begin(), after.end());
  for (const auto& [name, unused] : all) {
    if (before.count(name) && after.count(name) && before.at(name) == after.at(name)) continue;
    const std::string a = value_of(before, name), b = value_of(after, name);
    s << (s.tellp() > 0 ? ", " : "") << name << " " << a << " -> " << b;
  }
  return s.str();
}

}  // namespace ambid::daemons
