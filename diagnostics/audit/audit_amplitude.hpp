#pragma once
// Whether the nominal model's error depends on the excitation amplitude (a nonlinear effect,
// e.g. magnetic_saturation at large swings) or not (every linear one).
//
// The record is cut into `parts` contiguous parts. In each, the plant FRF of the measurement
// and of the replayed nominal model are estimated by the indirect closed-loop Welch estimator
// (audit_frf.hpp), and for every output/input pair the median over the well-determined lines
// (every input coherent with r, the measured element's relative variance small, so that
// noise does not bias its log magnitude) of log|G_meas / G_nominal|: the level of
// the model error in that part. For a linear model error the ratio is the same at every
// amplitude, whatever the excitation's spectrum (an FRF, unlike a time-domain residual, does
// not depend on the signal content), and noise only scatters it (uncorrelated with r, it does
// not bias the indirect estimate). Comparing the part of highest excitation rms with the part
// of lowest: z = (m_high - m_low) / se, the standard error from the lines' spread (median:
// 1.2533 sd / sqrt(lines / 2), neighbouring Welch lines being correlated). Not determinable (and then not dependent)
// when the parts' excitation rms differ by less than `min_spread`: a constant-amplitude record cannot tell.
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/experiment.hpp"
#include "diagnostics/audit/audit_replay.hpp"

namespace ambid::diag {

struct AmplitudePart {
  Segment samples;
  double excitation_rms = 0.0;   // over all excitation channels
  Eigen::MatrixXd log_ratio;     // outputs x inputs: median log|G_meas / G_nominal|
  Eigen::MatrixXd log_ratio_se;  // its standard error
  Eigen::MatrixXi lines;         // excited lines used per pair
};

struct AmplitudeDependence {
  bool determinable = false;
  std::string reason;                    // why not, when not determinable
  std::vector<AmplitudePart> parts;      // in record order
  Eigen::Index lowest = 0, highest = 0;  // parts of lowest and highest excitation rms
  double spread = 0.0;                   // their excitation rms ratio
  Eigen::MatrixXd z;                     // outputs x inputs (empty when not determinable)
  double max_abs_z = 0.0;
  bool dependent = false;  // max |z| above `z_threshold`
};

struct AmplitudeOptions {
  int parts = 6;
  Eigen::Index segment_samples = 512;  // Welch window within a part
  double min_spread = 1.5;
  double min_coherence = 0.5;           // of every input with r
  double max_relative_variance = 0.01;  // var G / |G|^2 of a line used (log bias < 0.5 %)
  double z_threshold = 4.0;             // over all pairs: beyond what the lines' scatter reaches
};

// `left_out` (per sample of the record, or empty): where a controller clamp acted; the Welch
// windows holding one are skipped. Error for inconsistent sizes; not determinable when a part
// is shorter than three Welch windows or its FRF cannot be estimated (a singular line, or too
// few windows without a clamp).
AmplitudeDependence amplitude_dependence(const Experiment& measured, const ReplayedLoop& nominal,
                                         const std::vector<bool>& left_out = {}, const AmplitudeOptions& options = {});

}  // namespace ambid::diag
