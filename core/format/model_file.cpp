#include "core/model_file.hpp"

#include <cmath>
#include <set>
#include <system_error>

#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "core/experiment_file.hpp"
#include "core/format/experiment_sidecar.hpp"
#include "core/format/experiment_text.hpp"
#include "core/format/json_fields.hpp"
#include "core/json_text.hpp"

// Required keys: format, plant_model, method, sample_time, discrete (A, B, C, D). Optional,
// empty when absent: continuous, no_continuous (why continuous is absent), parameters,
// physical, uncertainty, fit (and fit.nrmse): a method may give no physical parameters or no
// validation segment.

namespace ambid {
namespace {

using nlohmann::json;
using namespace json_fields;

const std::set<std::string> kTopKeys{"format",      "plant_model", "method",       "sample_time",
                                     "discrete",    "continuous",  "parameters",   "physical",
                                     "uncertainty", "fit",         "no_continuous"};

// The defined keys inside the objects whose unknown keys are kept under the same name in extra.
const std::map<std::string, std::set<std::string>> kNestedKeys{
    {"discrete", {"A", "B", "C", "D"}}, {"continuous", {"A", "B", "C", "D"}}, {"fit", {"nrmse"}}};

void keep_nested_unknown(const json& object, const std::string& path, json& extra) {
  json unknown = json::object();
  keep_unknown(object, kNestedKeys.at(path), unknown);
  if (!unknown.empty()) extra[path] = unknown;
}

template <typename System>
System parse_system(const json& value, const std::string& path, json& extra) {
  const json& s = as_object(value, path);
  keep_nested_unknown(s, path, extra);
  System system;
  const std::string rows = "an array of rows";
  system.A = as_matrix(require_key(s, path, "A", rows), path_of(path, "A"), 0);
  system.B = as_matrix(require_key(s, path, "B", rows), path_of(path, "B"), 0);
  system.C = as_matrix(require_key(s, path, "C", rows), path_of(path, "C"), system.A.cols());
  system.D = as_matrix(require_key(s, path, "D", rows), path_of(path, "D"), system.B.cols());
  return system;
}

template <typename System>
json system_json(const System& s) {
  return {{"A", matrix_json(s.A)}, {"B", matrix_json(s.B)}, {"C", matrix_json(s.C)}, {"D", matrix_json(s.D)}};
}

std::map<std::string, double> parse_numbers(const json& object, const std::string& path) {
  std::map<std::string, double> numbers;
  for (const auto& [key, value] : as_object(object, path).items()) numbers[key] = as_number(value, path_of(path, key));
  return numbers;
}

template <typename System>
void validate_system(const System& s, const std::string& path) {
  try {
    s.validate();
  } catch (const Error& e) {
    throw Error("key `" + path + "`: " + e.what());
  }
  if (s.states() == 0 || s.inputs() == 0 || s.outputs() == 0)
    throw Error("key `" + path + "` must have at least one state, input and output, got " + std::to_string(s.states()) +
                ", " + std::to_string(s.inputs()) + ", " + std::to_string(s.outputs()));
}

void validate_numbers(const std::map<std::string, double>& numbers, const std::string& path) {
  for (const auto& [key, value] : numbers)
    if (key.empty() || !std::isfinite(value))
      throw Error("key `" + path_of(path, key) + "` must be a finite number with a name, got " + number_text(value));
}

}  // namespace

void Model::validate() const {
  if (plant_model.empty()) throw Error("key `plant_model` must be a non-empty string");
  if (method.empty()) throw Error("key `method` must be a non-empty string");
  if (!(std::isfinite(sample_time) && sample_time > 0.0))
    throw Error("key `sample_time` must be a positive number of seconds, got " + number_text(sample_time));
  if (discrete.sample_time != sample_time)
    throw Error("the discrete system's sample time " + number_text(discrete.sample_time) +
                " differs from `sample_time` " + number_text(sample_time));
  validate_system(discrete, "discrete");
  if (continuous) validate_system(*continuous, "continuous");
  if (continuous && !no_continuous.empty())
    throw Error("key `no_continuous` says why there is no continuous system, but the model has one");
  validate_numbers(parameters, "parameters");
  validate_numbers(physical, "physical");
  validate_numbers(uncertainty, "uncertainty");
  validate_numbers(fit_nrmse, "fit.nrmse");
  for (const auto& [key, sigma] : uncertainty) {
    if (!parameters.count(key) && !physical.count(key))
      throw Error("key `uncertainty." + key + "` names no entry of `parameters` or `physical`");
    if (sigma < 0.0) throw Error("key `uncertainty." + key + "` must be >= 0 (one sigma), got " + number_text(sigma));
  }
  if (!extra.json().is_object()) throw Error("the unknown keys of a model must form an object");
  for (const auto& [key, value] : extra.json().items()) {
    const auto nested = kNestedKeys.find(key);
    if (nested == kNestedKeys.end()) {
      if (kTopKeys.count(key)) throw Error("the unknown keys of a model hold the defined key `" + key + "`");
      continue;
    }
    if (!value.is_object()) throw Error("the unknown keys of a model hold `" + key + "` as a non-object");
    if (key == "continuous" && !continuous)
      throw Error("the unknown keys of a model hold keys of `continuous`, but the model has no continuous system");
    for (const auto& defined : nested->second)
      if (value.contains(defined))
        throw Error("the unknown keys of a model hold the defined key `" + key + "." + defined + "`");
  }
}

json model_json(const Model& m) {
  m.validate();
  json j = json::object();
  j["format"] = kModelFormat;
  j["plant_model"] = m.plant_model;
  j["method"] = m.method;
  j["sample_time"] = m.sample_time;
  j["discrete"] = system_json(m.discrete);
  if (m.continuous) j["continuous"] = system_json(*m.continuous);
  if (!m.no_continuous.empty()) j["no_continuous"] = m.no_continuous;
  j["parameters"] = m.parameters;
  j["physical"] = m.physical;
  j["uncertainty"] = m.uncertainty;
  j["fit"] = {{"nrmse", m.fit_nrmse}};
  merge_unknown(j, m.extra.json());
  return j;
}

Model parse_model(const json& j) {
  if (!j.is_object()) wrong_type(j, "(root)", "an object");
  const std::string format = as_string(require_key(j, "", "format", "\"ambid-model/1\""), "format");
  if (format != kModelFormat)
    throw Error("key `format` must be \"" + std::string(kModelFormat) + "\", got " + quote_excerpt(format));
  Model m;
  m.plant_model = as_string(require_key(j, "", "plant_model", "a plant model name"), "plant_model");
  m.method = as_string(require_key(j, "", "method", "an identification method name"), "method");
  m.sample_time = as_number(require_key(j, "", "sample_time", "a number of seconds"), "sample_time");
  m.discrete = parse_system<DiscreteSystem>(require_key(j, "", "discrete", "an object with A, B, C, D"), "discrete",
                                            m.extra.json());
  m.discrete.sample_time = m.sample_time;
  if (const auto it = j.find("continuous"); it != j.end())
    m.continuous = parse_system<ContinuousSystem>(*it, "continuous", m.extra.json());
  if (const auto it = j.find("no_continuous"); it != j.end()) m.no_continuous = as_string(*it, "no_continuous");
  if (const auto it = j.find("parameters"); it != j.end()) m.parameters = parse_numbers(*it, "parameters");
  if (const auto it = j.find("physical"); it != j.end()) m.physical = parse_numbers(*it, "physical");
  if (const auto it = j.find("uncertainty"); it != j.end()) m.uncertainty = parse_numbers(*it, "uncertainty");
  if (const auto it = j.find("fit"); it != j.end()) {
    const json& fit = as_object(*it, "fit");
    if (const auto n = fit.find("nrmse"); n != fit.end()) m.fit_nrmse = parse_numbers(*n, "fit.nrmse");
    keep_nested_unknown(fit, "fit", m.extra.json());
  }
  keep_unknown(j, kTopKeys, m.extra.json());
  m.validate();
  return m;
}

Model read_model(const std::filesystem::path& path) {
  const std::string text = read_json_file(path);
  try {
    return parse_model(parse_sidecar_text(text));
  } catch (const Error& e) {
    throw Error(path.string() + ": " + e.what());
  }
}

void write_model(const Model& model, const std::filesystem::path& path) {
  std::string text;
  try {
    text = model_json(model).dump(2) + "\n";
  } catch (const json::exception& e) {  // a string that is not valid UTF-8
    throw Error("cannot encode the model " + path.string() + " as JSON: " + e.what());
  } catch (const Error& e) {
    throw Error(path.string() + ": " + e.what());
  }
  if (const auto dir = path.parent_path(); !dir.empty()) {
    std::error_code error;
    std::filesystem::create_directories(dir, error);
    if (error) throw Error("cannot create directory " + dir.string() + ": " + error.message());
  }
  write_files_atomically({{path, text}});
}

}  // namespace ambid
