#pragma once
// A window of closed-loop samples -> its model and its estimates (value and one-sigma
// uncertainty of every parameter and physical quantity): the one computation the identifier
// daemon and `ambid diagnose` share (services/daemons/identify_window.hpp,
// diagnostics/identified_estimates.hpp turn it into a bus message and an estimate window).
// Every sample of the window is fitted (no validation part) and the ERA methods run without
// the jackknife: diagnostics learns each parameter's window-to-window scatter from its baseline
// (diagnostics/monitor/baseline.hpp), and 8 leave-one-out fits per window would cost the stack
// its real-time headroom and `ambid diagnose` an 8-fold slowdown.
#include <map>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "core/experiment.hpp"
#include "core/model_file.hpp"
#include "identifier/identify_experiment.hpp"

namespace ambid::ident {

// Closed-loop (Lee ch. 2): unbiased off nominal (R1 +20 % reads +20 %) but without sigmas, so
// the diagnostics learn the scatter from the baseline windows; deadbeat reports sigmas but is
// biased when the controller's observer model is wrong.
inline constexpr const char* kDefaultWindowMethod = "closed-loop";

struct Estimate {
  std::string name;
  double value = 0.0;
  double sigma = 0.0;  // one standard deviation; 0: the method reports none
};

struct WindowIdentification {
  Model model;
  std::vector<Estimate> parameters;  // model.parameters with their sigmas, by name
  std::vector<Estimate> physical;    // model.physical with their sigmas, by name
};

// How a window is identified: `method` (methods.hpp), `skip_samples` leading samples dropped.
// Throws Error naming the known methods for an unknown one, and for skip < 0.
IdentifyOptions window_identify_options(const std::string& method, Eigen::Index skip_samples = 0);

// `values` with their `sigmas`. An empty `sigmas` (a method that reports none, e.g.
// closed-loop without the jackknife) gives sigma 0 for every value; otherwise throws Error
// "WHO: no uncertainty of NAME" for a value without one.
std::vector<Estimate> with_uncertainty(const std::map<std::string, double>& values,
                                       const std::map<std::string, double>& sigmas, const std::string& who);

// identify_experiment of the window with `options` (window_identify_options). Throws what it
// throws (InsufficientData for unexciting data), and NoContinuousEquivalent for a model with
// its discrete part only (Model::no_continuous): a window without physical parameters.
WindowIdentification identify_window(const Experiment& window, const IdentifyOptions& options);

// Why a window gave no estimates: `reason` a short fixed name (a metrics label, a key of
// diagnosis.json), `message` the error's words.
struct WindowFailure {
  std::string reason;
  std::string message;
};
// The reasons, in this order: "no_continuous_model" (NoContinuousEquivalent), "insufficient_data"
// (any other InsufficientData: too short, not exciting, rank deficient), "error" (any other Error).
const std::vector<std::string>& window_failure_reasons();
WindowFailure window_failure(const Error& error);

}  // namespace ambid::ident
