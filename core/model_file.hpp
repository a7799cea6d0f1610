#pragma once
// The identified-model file `model.json` (experiment-format.md, "Model file"): format
// ambid-model/1. The reader is strict (every error names the file, the key and what was
// expected); unknown keys are kept in Model::extra so a rewrite loses nothing.
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>

#include <nlohmann/json_fwd.hpp>

#include "core/json_value.hpp"
#include "core/state_space.hpp"

namespace ambid {

inline constexpr std::string_view kModelFormat = "ambid-model/1";

struct Model {
  std::string plant_model;   // e.g. "amb1dof_voltage"
  std::string method;        // deadbeat | okid | closed-loop | projection | ...
  double sample_time = 0.0;  // of `discrete` (> 0)
  DiscreteSystem discrete;   // deviations from the operating point, SI units
  std::optional<ContinuousSystem> continuous;
  // Why there is no `continuous` although the method gives one (key `no_continuous`, e.g. d2c
  // refused a discrete eigenvalue on the negative real axis); empty otherwise. Such a model has
  // its discrete part only: no physical coordinates, parameters or physical quantities.
  std::string no_continuous;
  std::map<std::string, double> parameters;   // model-structure parameters (v1..v9)
  std::map<std::string, double> physical;     // derived physical quantities (R1, kw1, ...)
  std::map<std::string, double> uncertainty;  // one sigma, keys of parameters or physical
  std::map<std::string, double> fit_nrmse;    // per output, on data the fit did not see
  // Unknown keys, mirroring the file: top-level ones at the top, unknown keys inside
  // `discrete`, `continuous` or `fit` under an object of that name. Never a defined key.
  JsonValue extra = JsonValue::object();

  // Throws Error naming the first violation: empty plant_model or method, sample_time not
  // positive and finite (or different from discrete.sample_time), inconsistent or non-finite
  // matrices, non-finite numbers, an uncertainty that is negative or names no parameter,
  // a `no_continuous` reason beside a continuous system.
  void validate() const;
};

// The JSON of a model (validates first).
nlohmann::json model_json(const Model& model);
// A model from parsed JSON; errors name the key path, not the file.
Model parse_model(const nlohmann::json& json);

// Reads `path`; every Error is prefixed with the file name.
Model read_model(const std::filesystem::path& path);
// Validates, then replaces `path` atomically (temporary file, fsync, rename), creating the
// parent directory. Numbers round-trip exactly.
void write_model(const Model& model, const std::filesystem::path& path);

}  // namespace ambid
