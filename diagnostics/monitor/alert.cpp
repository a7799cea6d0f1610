#include "diagnostics/alert.hpp"

#include <cmath>
#include <limits>
#include <string>

#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "diagnostics/fault_isolation.hpp"

namespace ambid::diag {
namespace {

constexpr Level kLevels[] = {Level::ok, Level::warn, Level::error, Level::stale};

const nlohmann::json& require_key(const nlohmann::json& j, const char* key) {
  const auto it = j.find(key);
  if (it == j.end()) throw Error(std::string("alert: missing key '") + key + "'");
  return *it;
}

std::string require_string(const nlohmann::json& j, const char* key) {
  const nlohmann::json& v = require_key(j, key);
  if (!v.is_string()) throw Error(std::string("alert: '") + key + "' must be a string, got " + v.dump());
  return v.get<std::string>();
}

double require_number(const nlohmann::json& v, const char* key) {
  if (!v.is_number()) throw Error(std::string("alert: '") + key + "' must be a number, got " + v.dump());
  const double x = v.get<double>();
  if (!std::isfinite(x)) throw Error(std::string("alert: '") + key + "' is not finite");
  return x;
}

}  // namespace

std::string_view to_string(Level level) {
  switch (level) {
    case Level::ok:
      return "OK";
    case Level::warn:
      return "WARN";
    case Level::error:
      return "ERROR";
    case Level::stale:
      return "STALE";
  }
  throw Error("unknown alert level value " + std::to_string(static_cast<int>(level)));
}

Level parse_level(std::string_view text) {
  for (Level l : kLevels)
    if (text == to_string(l)) return l;
  throw Error("unknown alert level '" + std::string(text) + "' (expected OK, WARN, ERROR or STALE)");
}

nlohmann::json to_json(const Alert& alert) {
  nlohmann::json j;
  j["time"] = alert.time;
  j["plant_id"] = alert.plant_id;
  j["level"] = to_string(alert.level);
  j["fault"] = alert.fault;
  j["channel"] = alert.channel ? nlohmann::json(*alert.channel) : nlohmann::json(nullptr);
  j["parameter"] = alert.parameter;
  j["value"] = alert.value;
  j["baseline"] = alert.baseline ? nlohmann::json(*alert.baseline) : nlohmann::json(nullptr);
  j["message"] = alert.message;
  return j;
}

Alert alert_from_json(const nlohmann::json& j) {
  if (!j.is_object()) throw Error("alert: expected a JSON object, got " + j.dump());
  Alert a;
  a.time = require_number(require_key(j, "time"), "time");
  a.plant_id = require_string(j, "plant_id");
  if (a.plant_id.empty()) throw Error("alert: 'plant_id' is empty");
  a.level = parse_level(require_string(j, "level"));
  a.fault = require_string(j, "fault");
  if (!is_known_fault(a.fault)) throw Error("alert: unknown fault '" + a.fault + "'");
  const nlohmann::json& channel = require_key(j, "channel");
  if (!channel.is_null()) {
    if (!channel.is_number_integer() || channel.get<long long>() < 1 ||
        channel.get<long long>() > std::numeric_limits<int>::max())
      throw Error("alert: 'channel' must be null or a positive integer, got " + channel.dump());
    a.channel = channel.get<int>();
  }
  a.parameter = require_string(j, "parameter");
  a.value = require_number(require_key(j, "value"), "value");
  const nlohmann::json& baseline = require_key(j, "baseline");
  if (!baseline.is_null()) a.baseline = require_number(baseline, "baseline");
  a.message = require_string(j, "message");
  return a;
}

}  // namespace ambid::diag
