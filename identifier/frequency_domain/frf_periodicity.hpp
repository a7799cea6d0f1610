#pragma once
// Periodic excitation recognised from the recorded references r alone (no description of the
// generator needed): the period, the whole periods recorded, and the DFT lines each reference
// excites. Rules:
// - The excited span runs from the first to the last sample where some reference is not
//   exactly zero (a generator switched on late or off early leaves r = 0 outside it).
// - The period is the smallest shift L (in samples, 1 <= L <= span / 2) at which every
//   reference repeats over the whole span: |r(n + L) - r(n)| <= tolerance * peak |r| of that
//   reference for every n with n + L inside the span. The span need not end on a whole period.
//   A period that is not a whole number of samples makes r repeat only after a multiple of it
//   that is (or never within the record: then r is not periodic).
// - A line k (0 < k < L/2) is excited by a reference when its one-period DFT amplitude is at
//   least line_threshold times that reference's strongest line (full, odd, zippered or
//   arbitrary grids; a repeated maximum-length PRBS excites every line).
#include <vector>

#include <Eigen/Core>

namespace ambid::ident {

struct PeriodicityOptions {
  double tolerance = 1e-6;       // relative to each reference's peak: round-off of the record
  double line_threshold = 1e-3;  // relative to the strongest line of the reference (-60 dB)
};

struct Periodicity {
  Eigen::Index first_sample = 0;                 // start of the excited span
  Eigen::Index span_samples = 0;                 // length of the excited span
  Eigen::Index period_samples = 0;               // 0: r does not repeat within the span
  Eigen::Index periods = 0;                      // whole periods in the span
  std::vector<std::vector<Eigen::Index>> lines;  // excited lines of each reference, increasing
  std::vector<Eigen::Index> all_lines;           // union of `lines`, increasing

  bool periodic() const { return period_samples > 0; }
};

// r: samples x references (deviations). Throws Error for non-finite data or options outside
// (0, 1).
Periodicity detect_periodicity(const Eigen::MatrixXd& r, const PeriodicityOptions& options = {});

// Whether every reference repeats with shift `shift` over [first, first + span) to the
// relative tolerance (the test of the rule above for one shift).
bool repeats_with_shift(const Eigen::MatrixXd& r, Eigen::Index first, Eigen::Index span, Eigen::Index shift,
                        double tolerance);

}  // namespace ambid::ident
