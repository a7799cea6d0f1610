#include "identifier/pem_warm_start.hpp"

#include <cmath>
#include <string>

#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "identifier/amb1dof_structure.hpp"

namespace ambid::ident {
namespace {

const std::string kWarmStartWho = "pem warm start";

double number(const nlohmann::json& value, const std::string& where) {
  if (!value.is_number() || !std::isfinite(value.get<double>()))
    throw Error(kWarmStartWho + ": " + where + " is not a finite number");
  return value.get<double>();
}

}  // namespace

PemWarmStart pem_warm_start(const Model& previous) {
  PemWarmStart start;
  const std::vector<std::string>& names = amb1dof_structure_names();
  for (std::size_t i = 0; i < names.size(); ++i) {
    const auto it = previous.parameters.find(names[i]);
    if (it == previous.parameters.end())
      throw Error(kWarmStartWho + ": the previous model (method '" + previous.method + "') has no " + names[i]);
    start.v(Eigen::Index(i)) = it->second;
  }
  const nlohmann::json& extra = previous.extra.json();
  if (!extra.is_object() || !extra.contains("pem") || !extra["pem"].contains("offset") ||
      !extra["pem"].contains("predictor_gain"))
    throw Error(kWarmStartWho + ": the previous model (method '" + previous.method +
                "') has no extra.pem.offset and extra.pem.predictor_gain (not a pem fit)");
  const nlohmann::json& offset = extra["pem"]["offset"];
  const nlohmann::json& gain = extra["pem"]["predictor_gain"];
  if (!offset.is_array() || offset.size() != 3) throw Error(kWarmStartWho + ": extra.pem.offset must hold 3 numbers");
  if (!gain.is_array() || gain.size() != 4)
    throw Error(kWarmStartWho + ": extra.pem.predictor_gain must hold 4 rows of 3");
  for (int i = 0; i < 3; ++i)
    start.offset(i) = number(offset[std::size_t(i)], "extra.pem.offset[" + std::to_string(i) + "]");
  for (int i = 0; i < 4; ++i) {
    const nlohmann::json& row = gain[std::size_t(i)];
    if (!row.is_array() || row.size() != 3)
      throw Error(kWarmStartWho + ": extra.pem.predictor_gain must hold 4 rows of 3");
    for (int j = 0; j < 3; ++j)
      start.predictor_gain(i, j) =
          number(row[std::size_t(j)], "extra.pem.predictor_gain[" + std::to_string(i) + "][" + std::to_string(j) + "]");
  }
  return start;
}

}  // namespace ambid::ident
