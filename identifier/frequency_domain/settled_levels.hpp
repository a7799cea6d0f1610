#pragma once
// A record of reference steps cut into its levels, for plant families whose linearisation
// changes with the level (the maglev's gap, `ambid frf` per level): the steps of a logged signal
// are where the mean over `window` after a sample differs from the mean over `window` before it
// by at least `step` (the sample of the largest difference in each run above step / 2); each
// level keeps its settled part, from `settle` after the step (after the record's start for the
// first) to `window` before the next; visits whose means lie within `merge` of each other are
// one level. The reference need not be logged (a rig's N x 3 records carry y, u, i only).
#include <vector>

#include <Eigen/Core>

namespace ambid::ident {

struct SettledLevelOptions {
  double window = 0.1;             // s: the means compared on either side of a sample (at least 2 samples)
  double step = 0.0;               // smallest step, in the signal's units; 0: 2 % of the median |signal|
  double settle = 0.3;             // s dropped after each step and at the record's start (the loop's transient)
  double merge = 0.0;              // visits with means closer than this are one level; 0: step / 2
  Eigen::Index min_samples = 128;  // settled samples (over all visits) a level needs to be kept
};

struct SettledSpan {
  Eigen::Index first = 0, samples = 0;
};

struct SettledLevel {
  double mean = 0.0;               // of the signal over the spans
  std::vector<SettledSpan> spans;  // its settled visits, in time order
  Eigen::Index samples() const;
};

struct SettledLevels {
  std::vector<SettledLevel> levels;  // in the order of their first visit
  std::vector<Eigen::Index> steps;   // the samples where the steps were found
  double step = 0.0, merge = 0.0;    // the thresholds used (resolved defaults)
};

// Error for a non-positive sample time, options out of range or a non-finite signal. A record
// without steps is one level (if long enough); levels shorter than min_samples are left out.
SettledLevels find_settled_levels(const Eigen::VectorXd& signal, double sample_time,
                                  const SettledLevelOptions& options = {});

}  // namespace ambid::ident
