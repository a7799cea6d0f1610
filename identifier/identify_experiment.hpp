#pragma once
// Identification of an experiment by method name -> the Model of model.json. The one entry
// point that `ambid identify`, the identifier daemon and `ambid diagnose` share.
//
// The methods (all time domain, all from closed-loop data), what each needs and the plant
// models it is defined for are listed in methods.hpp; `pem` is amb1dof_prediction_error.hpp.
// For `amb1dof_voltage` every 4-state result is brought to physical coordinates (x, x', i1, i2)
// and gives v1..v9 and the physical quantities (amb1dof_structure.hpp), each with its one-sigma
// uncertainty: deadbeat/deadbeat-iv from the least-squares covariance, pem from the QR of the
// prediction-error Jacobian (sandwich with the score covariance), okid/closed-loop/projection by the segment
// jackknife (segment_jackknife.hpp; `jackknife_segments` leave-one-out fits).
//
// The record is split: the first (1 - validation_fraction) is fitted, the rest only validates
// (fit.nrmse, closed-loop simulation with the recorded controller, closed_loop_validation.hpp).
// Samples where a controller clamp acted (controller.output_limits, state_limits;
// core/controller_replay.hpp) are not exogenous: the ARX methods (okid, closed-loop,
// projection) leave every equation whose window holds one out of their regressions, the others
// (which run a predictor or a realisation over contiguous samples) are fitted on the longest
// stretch of the fit window without one (a family whose methods fit the plant's own equations,
// plant_families.hpp `keeps_clamped`, keeps them all), and fit.nrmse does not score them. model.json says
// how many there were and what was done (extra "clamped_samples", and a warning).
// Nothing here stabilises an identified model: an unstable plant comes out unstable.
// When an ERA realisation has no continuous-time equivalent (d2c_zoh refuses a discrete
// eigenvalue on the closed negative real axis, as noise can put one there), the model keeps
// that discrete realisation in its own coordinates, with Model::no_continuous saying why and
// no parameters or physical quantities; no Error is thrown for it.
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/experiment.hpp"
#include "core/model_file.hpp"
#include "identifier/methods.hpp"
#include "identifier/pem_warm_start.hpp"

namespace ambid::ident {

struct IdentifyOptions {
  std::string method;                   // one of identification_methods() (methods.hpp)
  Eigen::Index order = 0;               // model states; 0: 4 for amb1dof_voltage, else ERA's suggestion
  Eigen::Index arx_order = 0;           // okid/closed-loop/projection; 0: grows with the fitted samples
                                        // (default_arx_order, identifier/time_domain/arx_order.hpp)
  Eigen::Index markov_count = 0;        // Markov parameters for ERA; 0: the first of default_markov_counts()
                                        // that determines the model order
  Eigen::Index skip_samples = 0;        // leading samples dropped (settling transient)
  Eigen::Index instrument_lags = 0;     // deadbeat-iv: r[k..k-lags]; 0: kDefaultInstrumentLags
  double validation_fraction = 0.25;    // in [0, 0.9]; 0: no validation (fit.nrmse empty)
  Eigen::Index jackknife_segments = 8;  // okid/closed-loop/projection: 0 (no uncertainty) or >= 2
  // pem: start from a previous fit (e.g. pem_warm_start(the previous window's model)) instead of
  // the closed-loop, deadbeat-iv and deadbeat starts; converges in a few iterations.
  std::optional<PemWarmStart> pem_warm_start;
};

inline constexpr Eigen::Index kDefaultInstrumentLags = 60;

// Throws Error naming the problem for an unknown method, an experiment the method cannot use
// (a plant model, controller or excitation it needs (methods.hpp) is missing, a controller
// with feedthrough from u), bad options; InsufficientData when the data cannot support the model (too short, not
// exciting, rank deficient). Warnings (e.g. no validation possible) go to
// Model::extra["warnings"] (an array of strings).
Model identify_experiment(const Experiment& experiment, const IdentifyOptions& options);

// Throws Error, as identify_experiment does, when the method cannot identify the experiment
// at all: an unknown method, a plant model it is not defined for, no excitation or no
// controller where it needs one. A caller that identifies many windows of one record refuses
// the record once with it; what fails later is a failure of that window.
void require_method_inputs(const Experiment& experiment, const std::string& method);

// Samples [begin, end) of `experiment` as an experiment of its own; the controller's
// initial_state becomes its state at `begin` (the controller replayed on the record).
Experiment experiment_segment(const Experiment& experiment, Eigen::Index begin, Eigen::Index end);

}  // namespace ambid::ident
