#include "diagnostics/audit/audit_rounding.hpp"

#include <nlohmann/json.hpp>

namespace ambid::diag {
namespace {

// extra.rig.settings.log_NAME per name, 0 where none.
Eigen::VectorXd rig_log_resolution(const Experiment& e, const std::vector<std::string>& names) {
  Eigen::VectorXd out = Eigen::VectorXd::Zero(std::ssize(names));
  const nlohmann::json& extra = e.extra.json();
  if (!extra.is_object() || !extra.contains("rig") || !extra["rig"].is_object()) return out;
  const nlohmann::json& settings = extra["rig"].value("settings", nlohmann::json::object());
  if (!settings.is_object()) return out;
  for (std::size_t j = 0; j < names.size(); ++j) {
    const auto it = settings.find("log_" + names[j]);
    if (it != settings.end() && it->is_number() && it->get<double>() > 0.0) out(Eigen::Index(j)) = it->get<double>();
  }
  return out;
}

}  // namespace

Eigen::VectorXd logging_resolution(const Experiment& e) { return rig_log_resolution(e, e.y_names); }

Eigen::VectorXd input_logging_resolution(const Experiment& e) { return rig_log_resolution(e, e.u_names); }

}  // namespace ambid::diag
