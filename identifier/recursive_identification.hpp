#pragma once
// Identification that goes on sample by sample: the recursive prediction-error method of the
// amb1dof_voltage structure (`rpem`, identifier/families/amb1dof_recursive_pem.hpp) fed with
// consecutive stretches of one plant's record, its estimates readable at any time. `ambid
// identify --method rpem` runs it over the whole record (detail::fit_rpem); the identifier
// daemon feeds it every batch and publishes at a configured rate.
//
// Start: the experiment's nominal model (the sidecar's parameters, the model the controller was
// designed on) with its Kalman predictor gain, the output scales from the first stretch.
// A stretch that does not follow the last one (a gap in time) restarts the predictor's state
// and sensitivities; one of another plant model or sample time restarts everything.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "core/experiment.hpp"
#include "identifier/amb1dof_structure.hpp"
#include "identifier/identify_window.hpp"

namespace ambid::ident {

class Amb1dofRecursivePem;
struct Amb1dofCoilOperatingPoint;

// The currents and voltages of `e`'s operating point (amb1dof_recursive_pem.hpp); Error
// (prefixed with `who`) naming a missing one.
Amb1dofCoilOperatingPoint amb1dof_coil_operating_point(const Experiment& e, const std::string& who);

struct RecursiveIdentifyOptions {
  // Memory 1 / (1 - forgetting) samples: 1 s at 10 kHz. 1: a growing memory (the batch limit),
  // for a plant that does not change: then the offsets do not random-walk either.
  double forgetting = 0.9999;
  // Variance per sample of the offsets' random walk (Amb1dofRecursivePemOptions); empty: the
  // family's default.
  std::optional<double> offset_random_walk = std::nullopt;
  // Per-window estimates (begin_window; Amb1dofRecursivePemOptions::window_estimates).
  bool window_estimates = false;
  // With window_estimates: a window whose estimate is further than this from its prior
  // (Amb1dofRecursivePem::window_surprise, in the prior's sigmas) is published from the plain RPEM
  // run beside it, and the next window held at that estimate (end_window).
  double follow_surprise = 4.0;
};

class RecursiveIdentification {
 public:
  explicit RecursiveIdentification(RecursiveIdentifyOptions options = {});
  ~RecursiveIdentification();
  RecursiveIdentification(RecursiveIdentification&&) noexcept;
  RecursiveIdentification& operator=(RecursiveIdentification&&) noexcept;

  // The samples of `stretch` (an amb1dof_voltage experiment with its nominal parameters; the
  // outputs x, i1, i2 and inputs u1, u2). Throws Error naming what the experiment lacks (another
  // plant family, a missing signal or parameter), InsufficientData when the first stretch's
  // outputs do not vary (no scale to start from) or, with window_estimates, when its excitation
  // moves r1 and r2 together (the batch method's check: the two coils cannot be told apart); the
  // estimator is then unchanged (the next stretch follows a gap).
  void add(const Experiment& stretch);

  // Amb1dofRecursivePem::begin_window (options.window_estimates, else Error): estimate() is
  // from now on that of the samples after this call, with the information so far scaled by
  // `carry` in (0, 1] (Error otherwise) as its prior. Nothing before the start.
  void begin_window(double carry);
  // The end of a window (options.window_estimates, else Error), before estimate(): a window far
  // from its prior (a step fault, a swapped plant), or one with a gap, is published from a plain
  // RPEM fed the same samples (theta at every sample, relaxed by carry at each begin_window: it
  // follows a step within a window or two), and begin_window then holds the predictor at that
  // estimate. (After a gap the held predictor's warm-up at a slow held predictor took up to 2
  // windows without information: the stack's swap then read R1 -17 % for 3 s.)
  void end_window();

  bool started() const { return estimator_ != nullptr; }
  std::uint64_t samples() const;      // since the start
  std::uint64_t projections() const;  // updates rejected for an unstable predictor

  // The current model (with window_estimates: the current window's): v1..v9, the physical quantities (with the nominal
  // L1, L2, m) and their sigmas, the continuous model and its zero-order hold; model.extra["rpem"] the samples,
  // forgetting, projections, jumps, commits, followed (windows published from the plain RPEM), offset, predictor gain
  // and prediction-error rms. Throws InsufficientData before the first sample.
  WindowIdentification estimate() const;

 private:
  RecursiveIdentifyOptions options_;
  std::unique_ptr<Amb1dofRecursivePem> estimator_;
  // With window_estimates: the plain RPEM beside it; whether the current window is published
  // from it; how many windows were.
  std::unique_ptr<Amb1dofRecursivePem> follower_;
  bool following_ = false, restarted_ = false;  // restarted_: a gap in the current window
  std::uint64_t followed_ = 0;
  // Of the started record: plant model, sample time, the nominal L1, L2, m, when the next sample is due.
  std::string plant_model_;
  double sample_time_ = 0.0;
  Amb1dofNominal nominal_;
  double next_time_ = 0.0;
};

}  // namespace ambid::ident
