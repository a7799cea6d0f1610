#include "identifier/plant_families.hpp"

#include <algorithm>

#include "identifier/families/amb1dof_realization.hpp"
#include "identifier/families/maglev_frf_structure.hpp"
#include "identifier/families/maglev_identification.hpp"

namespace ambid::ident {

const std::vector<IdentificationFamily>& identification_families() {
  static const std::vector<IdentificationFamily> families = {
      {"amb1dof_voltage",
       {"x", "i1", "i2"},
       {"u1", "u2"},
       4,
       add_amb1dof_structure,
       nullptr,
       {"deadbeat", "deadbeat-iv", "pem", "rpem"}},
      {"maglev1coil_voltage",
       {"x", "i"},
       {"u"},
       3,
       nullptr,
       fit_maglev_greybox_model,
       {"greybox"},
       true,
       maglev_frf_structure},
      // Seed 002's 10 states (5 positions, 5 rates); realisation coordinates only.
      {"lamstf", {"s1", "s2", "s3", "s4", "s5"}, {"i1", "i2", "i3", "i4", "i5"}, 10, nullptr, nullptr, {}},
  };
  return families;
}

std::string identification_family_names() {
  std::string out;
  for (const auto& f : identification_families()) out += (out.empty() ? "" : ", ") + f.name;
  return out;
}

const IdentificationFamily* find_identification_family(const std::string& model) {
  const auto& families = identification_families();
  const auto it = std::find_if(families.begin(), families.end(), [&](const auto& f) { return f.name == model; });
  return it == families.end() ? nullptr : &*it;
}

std::vector<std::string> families_offering(const std::string& method) {
  std::vector<std::string> out;
  for (const auto& f : identification_families())
    if (std::find(f.methods.begin(), f.methods.end(), method) != f.methods.end()) out.push_back(f.name);
  return out;
}

}  // namespace ambid::ident
