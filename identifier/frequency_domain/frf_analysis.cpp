#include "identifier/frf_analysis.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/controller_replay.hpp"
#include "core/error.hpp"
#include "identifier/frequency_domain/frf_levels.hpp"
#include "identifier/frequency_domain/frf_plan.hpp"
#include "identifier/frequency_domain/rational_fit_order.hpp"
#include "identifier/frf_welch.hpp"
#include "identifier/plant_families.hpp"

namespace ambid::ident {
namespace {

void fill_pairs(FrfReport& report, const Eigen::MatrixXd* coherence, double confidence) {
  const double factor =
      report.plant.has_variance() ? confidence_radius_factor(confidence, report.plant.variance_dof) : 0.0;
  for (Eigen::Index i = 0; i < report.plant.rows(); ++i) {
    for (Eigen::Index j = 0; j < report.plant.cols(); ++j) {
      PlantPair p;
      p.output = report.output_names[static_cast<std::size_t>(i)];
      p.input = report.input_names[static_cast<std::size_t>(j)];
      p.name = p.output + "/" + p.input;
      p.value = report.plant.element(i, j);
      if (report.plant.has_variance()) {
        p.variance = report.plant.element_variance(i, j);
        p.bound = (factor * p.variance.array()).sqrt().matrix();
      }
      if (coherence != nullptr) p.coherence = coherence->col(i);
      report.pairs.push_back(std::move(p));
    }
  }
}

// The family's structure on the plant FRF, or level by level where its linearisation changes
// with the level (frf_levels.hpp: `structured` is then the level at the operating point); a
// failure is a note.
void fit_structure(FrfReport& report, const Experiment& e, const std::vector<bool>& clamped) {
  const IdentificationFamily* family = find_identification_family(e.plant.model);
  if (!family || !family->frf_structure) return;
  const FrfStructure& structure = family->frf_structure();
  try {
    if (structure.level_signal.empty()) {
      report.structured = fit_structured_frf(e, report.plant, structure);
      return;
    }
    report.levels = fit_structure_per_level(e, structure, clamped);
    if (report.levels->at_operating_point)
      report.structured = report.levels->levels[*report.levels->at_operating_point].fit;
    else
      report.notes.push_back("structured fit of " + e.plant.model + ": no settled level at the operating point " +
                             structure.level_signal + " = " +
                             (e.operating_point.contains(structure.level_signal)
                                  ? std::to_string(e.operating_point.at(structure.level_signal))
                                  : std::string("(not given)")) +
                             "; see the levels");
  } catch (const Error& err) {
    report.notes.push_back(std::string("structured fit of ") + e.plant.model + ": " + err.what());
  }
}

void fit_pairs(FrfReport& report, const Experiment& e, const FrfAnalysisOptions& o) {
  const double f_top = o.fit_f_max > 0.0 ? o.fit_f_max : 0.1 / e.sample_time;
  std::vector<Eigen::Index> rows;
  for (Eigen::Index l = 0; l < report.frequency_hz.size(); ++l)
    if (report.frequency_hz(l) <= f_top && 2.0 * report.frequency_hz(l) * e.sample_time < 1.0) rows.push_back(l);
  if (rows.size() < 8) {
    report.notes.push_back("rational fit: fewer than 8 lines below " + std::to_string(f_top) + " Hz; no fit");
    return;
  }
  Eigen::VectorXd f(static_cast<Eigen::Index>(rows.size()));
  for (std::size_t k = 0; k < rows.size(); ++k) f(static_cast<Eigen::Index>(k)) = report.frequency_hz(rows[k]);
  OrderSearchOptions search;
  search.max_denominator_degree = o.fit_max_order;
  search.relative_degrees = {0, 1, 2, 3};
  search.fit.zoh_sample_time = e.sample_time;
  for (const PlantPair& pair : report.pairs) {
    Eigen::VectorXcd g(f.size());
    Eigen::VectorXd v(pair.variance.size() ? f.size() : 0);
    for (std::size_t k = 0; k < rows.size(); ++k) {
      g(static_cast<Eigen::Index>(k)) = pair.value(rows[k]);
      if (v.size()) v(static_cast<Eigen::Index>(k)) = pair.variance(rows[k]);
    }
    if (v.size() && !(v.minCoeff() > 0.0)) v.resize(0);  // noise-free lines: relative weights
    try {
      const OrderSelection sel = select_rational_order(f, g, v, search);
      report.fits.push_back(FittedPair{pair.name, pair.output, pair.input, sel.fit});
    } catch (const Error& err) {
      report.notes.push_back("rational fit of " + pair.name + ": " + err.what());
    }
  }
}

}  // namespace

FrfReport analyse_frf(const Experiment& e, const FrfAnalysisOptions& o) {
  e.validate();
  if (!e.has_excitation())
    throw InsufficientData("frf: the experiment records no excitation r; the closed-loop FRF needs one");
  if (!(o.confidence > 0.0 && o.confidence < 1.0))
    throw Error("frf: confidence must be in (0, 1), got " + std::to_string(o.confidence));
  FrfReport report;
  report.output_names = e.y_names;
  report.input_names = e.u_names;
  report.reference_names = e.r_names;
  Eigen::MatrixXd r = e.r_deviation(), u = e.u_deviation(), y = e.y_deviation();

  const nlohmann::json* d = excitation_description(e);
  report.excitation = excitation_kind(d);
  const Periodicity detected = detect_periodicity(r, o.periodicity);
  const std::optional<PeriodicPlan> periodic = plan_periodic(e, detected, d, o, report.notes, report.warnings);

  const ControllerReplay clamps = clamped_samples(e);  // not exogenous: no block holding one is averaged
  report.clamped_samples = clamps.clamped_samples;
  const std::vector<bool> left_out = clamps.clamped_samples > 0 ? clamps.clamped : std::vector<bool>{};

  const Eigen::MatrixXd* coherence = nullptr;
  Eigen::MatrixXd welch_coherence;
  if (periodic) {
    const Eigen::Index used = periodic->end_sample;
    PeriodicFrfOptions po = periodic->options;
    if (!left_out.empty()) po.left_out.assign(left_out.begin(), left_out.begin() + used);
    const PeriodicFrf p = estimate_periodic_frf(r.topRows(used), u.topRows(used), y.topRows(used), po);
    report.blocks_left_out = p.blocks_left_out;
    report.method = "periodic";
    report.periodic = periodic->summary;
    report.periodic->periods_used = p.periods_used;
    report.plant = p.plant;
    report.plant_direct = p.plant_direct;
    report.output_from_reference = p.output_from_reference;
    report.input_from_reference = p.input_from_reference;
    report.blocks = p.blocks;
    if (p.blocks < 2) report.notes.push_back("periodic analysis: one block only; no noise bounds");
  } else if (auto stepped = plan_stepped_sine(e, d, o, report.notes)) {
    const auto holds_clamp = [&](const SteppedSineStep& s) {
      if (left_out.empty() || s.measure_start < 0 || s.measure_start + s.measure_samples > std::ssize(left_out))
        return false;  // estimate_stepped_sine_frf refuses a window outside the record
      const auto first = left_out.begin() + s.measure_start;
      return std::find(first, first + s.measure_samples, true) != first + s.measure_samples;
    };
    report.blocks_left_out = static_cast<Eigen::Index>(std::erase_if(stepped->steps, holds_clamp));
    if (stepped->steps.empty())
      throw InsufficientData("frf: a controller clamp acts in the measurement window of every stepped-sine step");
    const SteppedSineFrf p = estimate_stepped_sine_frf(r, u, y, *stepped);
    report.method = "stepped_sine";
    report.plant = p.plant;
    report.plant_direct = p.plant_direct;
    report.output_from_reference = p.output_from_reference;
    report.input_from_reference = p.input_from_reference;
    report.blocks = p.plant.lines();
    report.notes.push_back("stepped sine: one window per frequency; no noise estimate");
  } else {
    WelchFrfOptions w;
    w.sample_time = e.sample_time;
    w.segment_samples = o.segment_samples;
    if (w.segment_samples == 0) {
      w.segment_samples = 64;
      while (w.segment_samples * 2 <= e.samples() / 8) w.segment_samples *= 2;
    }
    w.f_min = o.f_min;
    w.f_max = o.f_max;
    w.left_out = left_out;
    const WelchFrf p = estimate_welch_frf(r, u, y, w);
    report.blocks_left_out = p.skipped_segments;
    report.method = "welch";
    report.plant = p.plant;
    report.plant_direct = p.plant_direct;
    report.output_from_reference = p.output_from_reference;
    report.input_from_reference = p.input_from_reference;
    report.blocks = p.segments;
    welch_coherence = p.output_coherence;
    coherence = &welch_coherence;
  }
  if (report.clamped_samples > 0)
    report.notes.push_back(
        std::to_string(report.clamped_samples) +
        " samples with a controller clamp acting (not exogenous): " + std::to_string(report.blocks_left_out) +
        (report.method == "periodic" ? " blocks of periods (holding one, or right after one)"
         : report.method == "welch"  ? " Welch segments (holding one)"
                                     : " stepped-sine steps (holding one in their window)") +
        " left out");
  report.frequency_hz = report.plant.frequency_hz;
  fill_pairs(report, coherence, o.confidence);

  if (e.controller) {
    const LoopSignalNames signals{e.y_names, e.u_names, e.r_names};
    try {
      report.sensitivity = input_sensitivity_from_reference(report.input_from_reference, *e.controller, signals);
      report.sensitivity_peaks = sensitivity_peaks(*report.sensitivity, e.u_names, o.iso);
      report.sensitivity_peaks.push_back(max_singular_sensitivity_peak(*report.sensitivity, "sigma_max", o.iso));
    } catch (const Error& err) {
      report.notes.push_back(std::string("sensitivity: ") + err.what());
    }
    try {
      report.controller_check = check_controller(report.plant, report.output_from_reference, *e.controller, signals);
    } catch (const Error& err) {
      report.notes.push_back(std::string("controller check (seed 003 eq. 5): ") + err.what());
    }
  } else {
    report.notes.push_back("no controller recorded: no sensitivity and no controller check");
  }
  if (o.fit) fit_pairs(report, e, o);
  if (o.fit) fit_structure(report, e, left_out);
  return report;
}

}  // namespace ambid::ident
