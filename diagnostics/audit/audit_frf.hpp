#pragma once
// Where in frequency the nominal model is wrong: the plant FRF G (outputs x inputs) of the
// measurement and of the replayed models, each by the indirect closed-loop Welch estimator
// G = S_yr S_ur^+ (identifier/frf_welch.hpp; unbiased under feedback), and the element-wise
// ratio measured / model over the excited band.
#include <vector>

#include "core/experiment.hpp"
#include "diagnostics/audit/audit_replay.hpp"
#include "identifier/frf_types.hpp"

namespace ambid::diag {

struct AuditFrfs {
  ident::Frf measured, nominal, extended;    // plant G on the excited band
  ident::Frf ratio_nominal, ratio_extended;  // measured / model, element by element
  // Closed-loop y/r (T_yr) of the same three, for the report's loop Bode plot.
  ident::Frf loop_measured, loop_nominal, loop_extended;
};

// On `segment` of the record, without the Welch segments that hold a sample the segment
// leaves out (`measured` keeps its asymptotic variance); the excited band is the lines where every
// measured plant input is coherent with the excitation (multiple coherence >= min_coherence). All empty when the
// segment is too short for Welch averaging or no line is excited.
AuditFrfs audit_frfs(const Experiment& measured, const ReplayedLoop& nominal, const ReplayedLoop& extended,
                     const Segment& segment, double min_coherence = 0.5);

// The lines of pair (output i, input j) where the measured estimate is well determined,
// var G / |G|^2 <= max_relative_variance: elsewhere (a small cross-coupling, the position at
// high frequency) noise dominates the ratio and biases its magnitude upwards.
std::vector<Eigen::Index> determined_lines(const AuditFrfs& frfs, Eigen::Index i, Eigen::Index j,
                                           double max_relative_variance = 0.01);

}  // namespace ambid::diag
