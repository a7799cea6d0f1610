#include "diagnostics/audit/audit_rounding.hpp"

#include <nlohmann/json.hpp>

namespace ambid::diag {

Eigen::VectorXd logging_resolution(const Experiment& e) {
  Eigen::VectorXd out = Eigen::VectorXd::Zero(std::ssize(e.y_names));
  const nlohmann::json& extra = e.extra.json();
  if (!extra.is_object() || !extra.contains("rig") || !extra["rig"].is_object()) return out;
  const nlohmann::json& settings = extra["rig"].value("settings", nlohmann::json::object());
  if (!settings.is_object()) return out;
  for (std::size_t j = 0; j < e.y_names.size(); ++j) {
    const auto it = settings.find("log_" + e.y_names[j]);
    if (it != settings.end() && it->is_number() && it->get<double>() > 0.0) out(Eigen::Index(j)) = it->get<double>();
  }
  return out;
}

}  // namespace ambid::diag
