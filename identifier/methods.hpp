#pragma once
// The identification methods of identify_experiment.hpp, listed once: the dispatch and the
// requirement checks of identify_experiment, the command-line help (`ambid identify`,
// `ambid diagnose`, `ambid daemon identifier`), the error for an unknown name and the README's
// method list (checked by tests/identifier/method_registry_test.cpp) are built from it.
#include <string>
#include <string_view>
#include <vector>

namespace ambid {
struct Experiment;
struct Model;
}  // namespace ambid

namespace ambid::ident {

struct IdentifyOptions;

struct IdentificationMethod {
  std::string name;
  bool needs_controller = false;  // the controller that closed the loop (Experiment::controller)
  bool needs_r = false;           // the recorded excitation r (signals.r)
  // Defined only for the plant families that offer it (plant_families.hpp); else any model.
  bool family_bound = false;
  std::string description;  // one line
  // Fits `fit` (the part of the record to fit) into `model`. identify_experiment has checked
  // the requirements above and resolved the default instrument lags in `options` (the ARX
  // methods resolve their ARX order and Markov count on `fit`: time_domain/arx_order.hpp).
  void (*fit)(const Experiment& fit, const IdentifyOptions& options, Model& model) = nullptr;
  // How it leaves the samples where a controller clamp acted out of its fit (model.json
  // clamped_samples.fit). Empty: it cannot, and is fitted on the longest stretch of the fit
  // window without a clamp (identify_experiment.hpp).
  std::string leaves_out_clamped = {};
};

// Every method, in the order the help and the README list them.
const std::vector<IdentificationMethod>& method_registry();

// The names of method_registry(), in its order.
const std::vector<std::string>& identification_methods();

// The method called `name`. Throws Error "WHO: unknown method 'NAME' (expected one of ...)".
const IdentificationMethod& identification_method(const std::string& name, const std::string& who);

// The names joined by `separator`: "deadbeat | deadbeat-iv | ..." for a help line.
std::string method_names(std::string_view separator);

// One line per method under a header line: name, plant models, what it needs, description.
// The `--method` help of the commands shows it, and README.md carries it verbatim.
std::string method_table();

}  // namespace ambid::ident
