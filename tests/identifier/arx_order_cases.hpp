#pragma once
// The records of the ARX-order table (arx_order_table_slow_test.cpp) and of its row that the
// default suite holds (arx_order_row_test.cpp): the nonlinear amb1dof_voltage loop integrated
// with 10 sub-steps per sample (finer than the identified zero-order-hold model), a 2 V PRBS,
// 0.1 s of settling before the window, identified by okid / projection / closed-loop at a
// given ARX order and compared with the true linearisation (amb1dof_truth.hpp).
#include <cmath>
#include <map>
#include <string>

#include <nlohmann/json.hpp>

#include "amb1dof_truth.hpp"
#include "core/error.hpp"
#include "identifier/identify_experiment.hpp"
#include "plant_sim/closed_loop.hpp"
#include "plant_sim/scenario.hpp"

namespace ambid::ident::testing {

inline constexpr double kArxCaseSettle = 0.1;  // s before the window

struct ArxCase {
  Experiment record;
  std::map<std::string, double> truth;  // v1..v9
};

inline ArxCase arx_case(const std::string& controller, double window, double position_noise, double current_noise) {
  sim::ScenarioOptions o;
  o.controller = controller;
  o.duration = kArxCaseSettle + window;
  o.amplitude = 2.0;
  o.position_noise = position_noise;
  o.current_noise = current_noise;
  o.seed = 11 + static_cast<std::uint64_t>(std::lround(window * 10));
  sim::Scenario s = sim::build_scenario(o);
  s.options.substeps = 10;
  return {sim::run_closed_loop(*s.truth, s.header, s.options), true_structure(o)};
}

struct ArxCaseResult {
  double worst = 0.0;           // largest |relative error| of v1..v9
  double worst_physical = 0.0;  // of R1, R2, kw1, kw2 (v5, v7, v8, v9 times the nominal L)
  Eigen::Index order = 0;       // the ARX order used
  std::string error;            // the identifier's refusal, if any
};

// `order` 0: the default order.
inline ArxCaseResult identify_case(const ArxCase& c, const std::string& method, Eigen::Index order) {
  IdentifyOptions o;
  o.method = method;
  o.arx_order = order;
  o.validation_fraction = 0.0;
  o.jackknife_segments = 0;
  o.skip_samples = static_cast<Eigen::Index>(std::lround(kArxCaseSettle / c.record.sample_time));
  ArxCaseResult r;
  r.order = order;
  try {
    const Model m = identify_experiment(c.record, o);
    r.order = m.extra.json().at("arx").at("order").get<Eigen::Index>();
    for (const auto& [name, value] : c.truth) {
      const double e = std::abs(m.parameters.at(name) / value - 1.0);
      r.worst = std::max(r.worst, e);
      if (name == "v5" || name == "v7" || name == "v8" || name == "v9")
        r.worst_physical = std::max(r.worst_physical, e);
    }
  } catch (const Error& e) {
    r.error = e.what();
  }
  return r;
}

}  // namespace ambid::ident::testing
