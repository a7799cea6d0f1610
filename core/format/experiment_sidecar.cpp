#include "core/format/experiment_sidecar.hpp"

#include <algorithm>
#include <cmath>

#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "core/experiment_io.hpp"
#include "core/format/experiment_text.hpp"
#include "core/format/json_fields.hpp"
#include "core/json_text.hpp"

// Required keys, chosen from the contract: `format`, `name`, `sample_time`, `plant.model`,
// `plant.parameters`, `signals.y`, `signals.u` and `operating_point`, which must give a value
// for every y and u signal (the contract calls it "the value of every named signal" and lets
// only excitation signals default to 0). Optional: `signals.r` (no excitation recorded) and
// `controller` (only methods that need it refuse to run); inside `controller` everything but
// `initial_state` (default zero), `output_limits` and `state_limits` (no clamps) is required.

namespace ambid {
namespace {

using nlohmann::json;
using namespace json_fields;

// `null` (no limit) or `[lo, hi]` whose entries are numbers or null (no bound on that side).
std::vector<Limit> parse_limits(const json& value, const std::string& path) {
  if (!value.is_array()) wrong_type(value, path, "an array of [lo, hi] pairs or nulls");
  std::vector<Limit> limits(value.size());
  for (std::size_t i = 0; i < value.size(); ++i) {
    const json& pair = value[i];
    const std::string at = indexed(path, i);
    if (pair.is_null()) continue;
    if (!pair.is_array() || pair.size() != 2) wrong_type(pair, at, "[lo, hi] or null");
    if (!pair[0].is_null()) limits[i].lo = as_number(pair[0], indexed(at, 0));
    if (!pair[1].is_null()) limits[i].hi = as_number(pair[1], indexed(at, 1));
  }
  return limits;
}

json limits_json(const std::vector<Limit>& limits) {
  json out = json::array();
  auto bound = [](double v) { return std::isfinite(v) ? json(v) : json(); };
  for (const Limit& l : limits)
    out.push_back(std::isfinite(l.lo) || std::isfinite(l.hi) ? json::array({bound(l.lo), bound(l.hi)}) : json());
  return out;
}

StateSpaceController parse_controller(const json& value, json& extra) {
  const std::string p = "controller";
  const json& c = as_object(value, p);
  StateSpaceController k;
  k.kind = as_string(require_key(c, p, "kind", "\"state_space\""), "controller.kind");
  k.sample_time = as_number(require_key(c, p, "sample_time", "a number of seconds"), "controller.sample_time");
  k.inputs = as_names(require_key(c, p, "inputs", "an array of signal names"), "controller.inputs");
  k.outputs = as_names(require_key(c, p, "outputs", "an array of u signal names"), "controller.outputs");
  const auto inputs = static_cast<Eigen::Index>(k.inputs.size());
  const std::string matrix = "an array of rows";
  k.A = as_matrix(require_key(c, p, "A", matrix), "controller.A", 0);
  k.B = as_matrix(require_key(c, p, "B", matrix), "controller.B", inputs);
  k.C = as_matrix(require_key(c, p, "C", matrix), "controller.C", 0);
  k.D = as_matrix(require_key(c, p, "D", matrix), "controller.D", inputs);
  if (const auto it = c.find("initial_state"); it != c.end()) {
    k.initial_state = as_vector(*it, "controller.initial_state");
    if (k.initial_state.size() != k.states())  // present but empty would silently mean zero
      throw Error("key `controller.initial_state` must have " + std::to_string(k.states()) + " entries (states), got " +
                  std::to_string(k.initial_state.size()));
  }
  if (const auto it = c.find("output_limits"); it != c.end())
    k.output_limits = parse_limits(*it, "controller.output_limits");
  if (const auto it = c.find("state_limits"); it != c.end())
    k.state_limits = parse_limits(*it, "controller.state_limits");
  json unknown = json::object();
  keep_unknown(c, defined_sidecar_keys().at(p), unknown);
  if (!unknown.empty()) extra[p] = unknown;
  return k;
}

}  // namespace

const std::map<std::string, std::set<std::string>>& defined_sidecar_keys() {
  static const std::map<std::string, std::set<std::string>> keys{
      {"", {"format", "name", "sample_time", "plant", "signals", "operating_point", "controller"}},
      {"plant", {"model", "parameters"}},
      {"signals", {"y", "u", "r"}},
      {"controller",
       {"kind", "sample_time", "inputs", "outputs", "A", "B", "C", "D", "initial_state", "output_limits",
        "state_limits"}}};
  return keys;
}

json parse_sidecar_text(const std::string& text) {
  // The open objects and arrays, each with its key path ("[]" for any array element) and, for
  // an object, the keys seen so far.
  struct Open {
    std::string path;
    bool is_object;
    std::set<std::string> keys;
  };
  std::vector<Open> open;
  std::string last_key;
  auto child_path = [&] {
    if (open.empty()) return std::string();
    return open.back().is_object ? path_of(open.back().path, last_key) : open.back().path + "[]";
  };
  const json::parser_callback_t check_keys = [&](int, json::parse_event_t event, json& parsed) {
    using E = json::parse_event_t;
    if (event == E::object_start || event == E::array_start) {
      open.push_back({child_path(), event == E::object_start, {}});
    } else if (event == E::object_end || event == E::array_end) {
      open.pop_back();
    } else if (event == E::key) {
      last_key = parsed.get<std::string>();
      if (!open.back().keys.insert(last_key).second)
        throw Error("key `" + path_of(open.back().path, last_key) + "` appears twice in one object");
    }
    return true;
  };
  check_json_bounds(text);  // before the parser: its cost grows with the square of the depth
  try {
    return json::parse(text, check_keys);
  } catch (const json::exception& e) {  // syntax, or a number beyond the range of double
    throw Error(std::string("malformed JSON: ") + e.what());
  }
}

Experiment parse_sidecar(const json& sidecar, std::vector<std::string>& warnings) {
  if (!sidecar.is_object()) wrong_type(sidecar, "(root)", "an object");
  Experiment e;
  e.extra = JsonValue::object();
  const std::string format = as_string(require_key(sidecar, "", "format", "\"ambid-experiment/1\""), "format");
  if (format != kExperimentFormat)
    throw Error("key `format` must be \"" + std::string(kExperimentFormat) + "\", got " + quote_excerpt(format));
  e.name = as_string(require_key(sidecar, "", "name", "a string"), "name");
  e.sample_time = as_number(require_key(sidecar, "", "sample_time", "a number of seconds"), "sample_time");

  const json& plant = as_object(require_key(sidecar, "", "plant", "an object"), "plant");
  e.plant.model = as_string(require_key(plant, "plant", "model", "a plant model name"), "plant.model");
  const json& parameters =
      as_object(require_key(plant, "plant", "parameters", "an object of numbers"), "plant.parameters");
  for (const auto& [key, value] : parameters.items())
    e.plant.parameters[key] = as_number(value, "plant.parameters." + key);

  const json& signals = as_object(require_key(sidecar, "", "signals", "an object"), "signals");
  e.y_names = as_names(require_key(signals, "signals", "y", "an array of output names"), "signals.y");
  e.u_names = as_names(require_key(signals, "signals", "u", "an array of plant input names"), "signals.u");
  if (const auto it = signals.find("r"); it != signals.end()) e.r_names = as_names(*it, "signals.r");

  const json& op = as_object(require_key(sidecar, "", "operating_point", "an object of numbers"), "operating_point");
  const std::vector<std::string> names = e.signal_names();
  for (const auto& [key, value] : op.items()) {
    e.operating_point[key] = as_number(value, "operating_point." + key);
    if (std::find(names.begin(), names.end(), key) == names.end())
      warnings.push_back("operating_point." + key + " names no signal of signals.y/u/r; kept and ignored");
  }

  if (const auto it = sidecar.find("controller"); it != sidecar.end())
    e.controller = parse_controller(*it, e.extra.json());

  keep_unknown(sidecar, defined_sidecar_keys().at(""), e.extra.json());
  json plant_extra = json::object(), signals_extra = json::object();
  keep_unknown(plant, defined_sidecar_keys().at("plant"), plant_extra);
  keep_unknown(signals, defined_sidecar_keys().at("signals"), signals_extra);
  if (!plant_extra.empty()) e.extra.json()["plant"] = plant_extra;
  if (!signals_extra.empty()) e.extra.json()["signals"] = signals_extra;

  e.validate_metadata();
  return e;
}

json sidecar_json(const Experiment& e) {
  e.validate_metadata();
  json j = json::object();
  j["format"] = kExperimentFormat;
  j["name"] = e.name;
  j["sample_time"] = e.sample_time;
  j["plant"] = {{"model", e.plant.model}, {"parameters", e.plant.parameters}};
  j["signals"] = {{"y", e.y_names}, {"u", e.u_names}};
  if (!e.r_names.empty()) j["signals"]["r"] = e.r_names;
  j["operating_point"] = e.operating_point;
  if (e.controller) {
    const StateSpaceController& k = *e.controller;
    json& c = j["controller"];
    c = {{"kind", k.kind},        {"sample_time", k.sample_time}, {"inputs", k.inputs},    {"outputs", k.outputs},
         {"A", matrix_json(k.A)}, {"B", matrix_json(k.B)},        {"C", matrix_json(k.C)}, {"D", matrix_json(k.D)}};
    if (k.initial_state.size() > 0)
      c["initial_state"] = std::vector<double>(k.initial_state.data(), k.initial_state.data() + k.initial_state.size());
    if (!k.output_limits.empty()) c["output_limits"] = limits_json(k.output_limits);
    if (!k.state_limits.empty()) c["state_limits"] = limits_json(k.state_limits);
  }
  // validate_metadata() guaranteed extra never collides with a defined key.
  merge_unknown(j, e.extra.json());
  return j;
}

}  // namespace ambid
