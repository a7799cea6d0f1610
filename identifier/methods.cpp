#include "identifier/methods.hpp"

#include <algorithm>

#include "core/error.hpp"
#include "identifier/plant_families.hpp"
#include "identifier/time_domain/method_fits.hpp"

namespace ambid::ident {
namespace {

std::string join(const std::vector<std::string>& items, std::string_view separator) {
  std::string out;
  for (const std::string& item : items) out += (out.empty() ? "" : std::string(separator)) + item;
  return out;
}

std::string needs(const IdentificationMethod& m) {
  if (m.needs_controller && m.needs_r) return "controller, r";
  if (m.needs_controller) return "controller";
  if (m.needs_r) return "r";
  return "-";
}

std::string padded(const std::string& text, std::size_t width) {
  return text + std::string(width > text.size() ? width - text.size() : 0, ' ');
}

constexpr const char* kArxLeavesOut = "left out of the ARX regressions (every equation whose window holds one)";

}  // namespace

const std::vector<IdentificationMethod>& method_registry() {
  static const std::vector<IdentificationMethod> methods = {
      {"deadbeat", true, false, true, "seed 000 physical realisation; sigmas from its least-squares covariance",
       detail::fit_deadbeat},
      {"deadbeat-iv", true, true, true,
       "deadbeat by instrumental variables (the delayed r): consistent under sensor noise", detail::fit_deadbeat_iv},
      {"okid", false, false, false, "ARX of y on the plant input u, OKID Markov parameters, ERA", detail::fit_okid,
       kArxLeavesOut},
      {"closed-loop", true, true, false, "known-controller identification from r to y (Lee ch. 2)",
       detail::fit_closed_loop, kArxLeavesOut},
      {"projection", false, true, false, "projection filters with unknown feedback uf = u - r (Lee ch. 4)",
       detail::fit_projection, kArxLeavesOut},
      {"pem", true, true, true,
       "prediction error (exact sensitivities, QR Levenberg-Marquardt) from the best of closed-loop, deadbeat-iv, "
       "deadbeat, nominal; noise-consistent",
       detail::fit_pem,
       "left out of the prediction-error cost (the error of every sample whose one-step prediction used a clamped "
       "input; the predictor is driven by the clamped input, as replay applies it)"},
      {"rpem", false, false, true,
       "recursive prediction error (seed 001: sample by sample, UD covariance, forgetting 1 s) from the nominal "
       "model; the estimate at the record's end",
       detail::fit_rpem},
      {"greybox", false, false, true,
       "physical parameters on the family's nonlinear model from x, i, u (no controller or r needed)",
       detail::fit_greybox},
  };
  return methods;
}

const std::vector<std::string>& identification_methods() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> out;
    for (const IdentificationMethod& m : method_registry()) out.push_back(m.name);
    return out;
  }();
  return names;
}

const IdentificationMethod& identification_method(const std::string& name, const std::string& who) {
  const auto& methods = method_registry();
  const auto it = std::find_if(methods.begin(), methods.end(), [&](const auto& m) { return m.name == name; });
  if (it == methods.end())
    throw Error(who + ": unknown method '" + name + "' (expected one of " + method_names(", ") + ")");
  return *it;
}

std::string method_names(std::string_view separator) { return join(identification_methods(), separator); }

std::string method_table() {
  const std::vector<std::string> header = {"method", "plant", "needs", "what it does"};
  std::vector<std::vector<std::string>> rows = {header};
  for (const IdentificationMethod& m : method_registry())
    rows.push_back({m.name, m.family_bound ? join(families_offering(m.name), ", ") : "any", needs(m), m.description});
  std::vector<std::size_t> width(header.size() - 1, 0);
  for (const auto& row : rows)
    for (std::size_t c = 0; c < width.size(); ++c) width[c] = std::max(width[c], row[c].size());
  std::string out;
  for (const auto& row : rows) {
    for (std::size_t c = 0; c < width.size(); ++c) out += padded(row[c], width[c] + 2);
    out += row.back() + "\n";
  }
  return out;
}

}  // namespace ambid::ident
