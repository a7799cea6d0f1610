#pragma once
// The family's structure fitted level by level (`ambid frf` on records of reference steps, for a
// family whose linearisation changes with the level: FrfStructure::level_signal). One Welch FRF
// over the whole record averages the plant over the levels (the maglev between 13 and 16 mm,
// where n_i g / i0 changes 2.3x, read its unstable pole 8 % high); here the record is cut into
// its settled levels (settled_levels.hpp, on the level signal), and each level gets
// - its own operating point: the means of every y and u over its settled spans;
// - its plant FRF by Welch (frf_welch.hpp) over those spans only: r, u and y detrended per span
//   (a level's offset and the ramp that the contract's integrator puts into r away from the
//   recorded operating point are no excitation), segments of the largest power of two that
//   fits twice into the longest span (at least 64), overlapping by 75 % (over seven rig
//   records, 35 levels: pole error rms 2.65 % against 3.09 % at 50 %, |error| / sigma rms 0.97),
//   every segment holding a sample outside the spans or a clamped one left out;
// - the structure fitted to that FRF from the family's start at the level's point, with the
//   derived quantities (the unstable pole) and their one-sigma uncertainties.
// The answer at the record's operating point (the one the user names in the sidecar, measured
// on the rig) is the level whose mean of the level signal lies within the segmentation's merge
// distance of it; where the family can carry a level's structure to another point, all levels
// pooled there too (PooledStructure), whether a level lies at the point or not.
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/experiment.hpp"
#include "identifier/frequency_domain/frf_structured.hpp"
#include "identifier/frequency_domain/settled_levels.hpp"

namespace ambid::ident {

struct LevelStructuredFit {
  std::map<std::string, double> operating_point;  // the level's means of every y and u
  std::vector<SettledSpan> spans;
  Eigen::Index samples = 0, segment_samples = 0, segments = 0;
  std::optional<StructuredFrfFit> fit;  // empty when it failed (`note` says why)
  std::string note;
};

// The derived quantities at the operating point from every fitted level, each level's theta
// carried there by the family's law (FrfStructure::transport) with its covariance, pooled by
// inverse variance; the sigma widened by the Birge ratio sqrt(chi^2 / (levels - 1)) when the
// levels disagree beyond their sigmas (a law the record does not follow).
struct PooledStructure {
  std::vector<std::string> derived_names;
  Eigen::VectorXd derived_value, derived_sigma;
  Eigen::VectorXd birge_ratio;  // per derived quantity
  int levels = 0;
};

struct LevelStructuredAnalysis {
  std::string level_signal;
  std::vector<LevelStructuredFit> levels;         // in the order of their first visit
  std::optional<std::size_t> at_operating_point;  // the level at the record's operating point
  double merge = 0.0;                             // the distance that decides it (signal units)
  // At the record's operating point from all levels (a family with a transport, two fitted
  // levels or more); empty otherwise.
  std::optional<PooledStructure> pooled;
  std::string pooled_note;  // why it could not be carried there
};

// `clamped`: per sample, a controller clamp acted (not exogenous); empty: none. Error when the
// structure has no level signal, the experiment lacks it among its outputs or has no r;
// InsufficientData when no level is long enough for two Welch segments.
LevelStructuredAnalysis fit_structure_per_level(const Experiment& experiment, const FrfStructure& structure,
                                                const std::vector<bool>& clamped,
                                                const SettledLevelOptions& options = {});

}  // namespace ambid::ident
