// The audit on independent truths (audit_independent_cases.hpp), at length:
// - false acceptance over 120 clean records from the four controllers: at most what the
//   stated rate (false_acceptance 0.01) allows with a binomial margin (P(more) < 1 %);
// - detection probability against effect size, 0.1x to 10x each effect's catalogue scale at
//   0.1 um / 1 mA, written to audit_detection.csv and audit_detection.svg in the build
//   directory (README "Hidden effects and the model audit"), with the size at which each
//   effect is found 90 % of the time. AMBID_AUDIT_SWEEP_EFFECTS (comma-separated) sweeps only
//   those effects. Seeds per size: AMBID_AUDIT_SWEEP_SEEDS (default 3);
//   at 3 (the README's run) the size of every effect stated_size_for_90() holds must be the
//   README's within a factor of 2 (about one step of the sweep's grid; "never" stays never).
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>

#include <gtest/gtest.h>

#include "audit_independent_cases.hpp"
#include "core/error.hpp"
#include "diagnostics/audit.hpp"
#include "services/report/atomic_file.hpp"
#include "services/report/svg.hpp"

namespace ambid::diag {
namespace audit_independent_slow_test {

// The smallest k with P(X > k) < tail for X ~ Binomial(n, p).
int binomial_bound(int n, double p, double tail) {
  double cdf = 0.0, term = std::pow(1.0 - p, n);
  for (int k = 0; k <= n; ++k) {
    cdf += term;
    if (1.0 - cdf < tail) return k;
    term *= double(n - k) / double(k + 1) * p / (1.0 - p);
  }
  return n;
}

TEST(AuditIndependentSlow, FalseAcceptanceOverCleanRecordsIsWithinTheStatedRate) {
  const auto& controllers = test_support::effect_record_controllers();
  constexpr int kRecords = 120;
  int named = 0;
  double rate = 0.0;
  for (int s = 0; s < kRecords; ++s) {
    const std::string& controller = controllers[std::size_t(s) % controllers.size()];
    const auto seed = std::uint64_t(7000 + s);
    const AuditResult r = run_audit(test_support::simulate_effect_record(testing::realistic_record(controller, seed)));
    rate = r.false_acceptance;
    if (r.cause != "none") {
      ++named;
      std::cerr << controller << " seed " << seed << " named " << r.cause << ": " << r.findings.front().evidence
                << "\n";
    }
  }
  const int bound = binomial_bound(kRecords, rate, 0.01);
  std::cerr << named << " of " << kRecords << " clean records got a cause (stated rate " << rate << ", bound " << bound
            << ")\n";
  EXPECT_LE(named, bound);
}

struct Point {
  double multiple = 0.0;
  // found: the cause and its channel; partner: the partner of its group (accepted_causes) or
  // the wrong channel; unrelated: any other catalogue cause ("unexplained", the nominal model
  // rejected with no cause, is a miss like "none", not a wrong name); unstable: the loop did not
  // survive.
  int runs = 0, found = 0, partner = 0, unrelated = 0, unstable = 0;
  double probability() const { return runs ? double(found) / runs : NAN; }
};

// Log-interpolated multiple where the detection probability first reaches 0.9 and stays.
double size_for_90(const std::vector<Point>& curve) {
  for (std::size_t i = 0; i < curve.size(); ++i) {
    const bool stays = std::all_of(curve.begin() + std::ptrdiff_t(i), curve.end(),
                                   [](const Point& p) { return p.runs == 0 || p.probability() >= 0.9; });
    if (curve[i].runs == 0 || curve[i].probability() < 0.9 || !stays) continue;
    if (i == 0 || curve[i - 1].runs == 0) return curve[i].multiple;
    const Point &a = curve[i - 1], &b = curve[i];
    const double f = (0.9 - a.probability()) / (b.probability() - a.probability());
    return std::exp(std::log(a.multiple) + f * (std::log(b.multiple) - std::log(a.multiple)));
  }
  return NAN;
}

// The sizes (multiples of the catalogue scale) from which each effect is found 90 % of the
// time as the README states them, measured with 3 seeds per point (2026-12-03, after the
// head-to-head choice, audit_rivals.hpp); NaN: at no size of the sweep for good.
const std::map<std::string, double>& stated_size_for_90() {
  static const std::map<std::string, double> sizes = {
      {"coil_resistance", 1.62}, {"amplifier_gain", 0.81}, {"amplifier_bandwidth", 8.1},   {"eddy_current", NAN},
      {"sensor_delay", 4.56},    {"sensor_gain", NAN},     {"flexible_mode", NAN},         {"magnetic_saturation", NAN},
      {"air_gap", 1.62},         {"rotor_mass", NAN},      {"harmonic_disturbance", 4.36}, {"force_factor", 4.36}};
  return sizes;
}

TEST(AuditIndependentSlow, DetectionProbabilityAgainstEffectSize) {
  const char* env = std::getenv("AMBID_AUDIT_SWEEP_SEEDS");
  const int seeds = env ? std::max(1, std::atoi(env)) : 3;
  const std::vector<double> multiples = {0.1, 0.2, 0.5, 1.0, 2.0, 5.0, 10.0};
  const auto& controllers = test_support::effect_record_controllers();
  std::map<std::string, std::vector<Point>> curves;
  std::ofstream csv(std::string(AMBID_BINARY_DIR) + "/audit_detection.csv");
  csv << "effect,multiple,runs,found,partner_or_channel,unrelated_cause,unstable,probability\n";
  const char* only = std::getenv("AMBID_AUDIT_SWEEP_EFFECTS");
  auto swept = [&](const std::string& name) {
    if (!only) return true;
    std::istringstream list(only);
    for (std::string item; std::getline(list, item, ',');)
      if (item == name) return true;
    return false;
  };
  const auto names = testing::independent_effect_names();
  for (std::size_t n = 0; n < names.size(); ++n) {
    const std::string& name = names[n];
    if (!swept(name)) continue;
    for (double m : multiples) {
      Point p;
      p.multiple = m;
      for (int s = 0; s < seeds; ++s) {
        const auto seed = std::uint64_t(20000 + 1000 * n + 10 * std::size_t(m * 10) + std::size_t(s));
        const sim::Effect truth = testing::effect_at(name, m, seed);
        test_support::EffectRecordOptions o =
            testing::realistic_record(controllers[std::size_t(s) % controllers.size()], seed);
        o.effects = {truth};
        Experiment record;
        try {
          record = test_support::simulate_effect_record(o);
        } catch (const Error&) {
          ++p.unstable;  // the recorded controller cannot hold the rotor with this effect
          continue;
        }
        AuditResult r;
        try {
          r = run_audit(record);
        } catch (const Error& e) {
          ADD_FAILURE() << name << " x" << m << " " << o.controller << ": " << e.what();
          continue;
        }
        ++p.runs;
        const bool right = r.cause == name && r.findings.front().effect.channel == truth.channel;
        const auto group = testing::accepted_causes(name);
        const bool in_group = std::find(group.begin(), group.end(), r.cause) != group.end();
        p.found += right ? 1 : 0;
        p.partner += !right && in_group ? 1 : 0;
        p.unrelated += r.cause != "none" && r.cause != "unexplained" && !in_group ? 1 : 0;
      }
      csv << name << "," << m << "," << p.runs << "," << p.found << "," << p.partner << "," << p.unrelated << ","
          << p.unstable << "," << p.probability() << "\n";
      curves[name].push_back(p);
    }
  }
  report::Axes axes;
  axes.x_label = "effect size / catalogue scale";
  axes.y_label = "P(cause and channel named)";
  axes.log_x = true;
  axes.y_range = report::Range{0.0, 1.0};
  axes.reference_lines.push_back({0.9, "0.9", "#888888", "4 3"});
  for (const auto& [name, curve] : curves) {
    std::vector<double> x, y;
    for (const Point& p : curve) x.push_back(p.multiple), y.push_back(p.probability());
    axes.series.push_back(report::line(name, x, y));
    const double s90 = size_for_90(curve);
    std::cerr << name << ": found 90 % of the time from " << s90 << " x its scale\n";
    csv << "# " << name << " size_for_90 " << s90 << "\n";
    if (seeds == 3 && stated_size_for_90().contains(name)) {
      const double stated = stated_size_for_90().at(name);
      if (std::isnan(stated))
        EXPECT_TRUE(std::isnan(s90)) << name << ": found 90 % of the time from " << s90 << " x, stated never";
      else
        EXPECT_NEAR(std::log(s90), std::log(stated), std::log(2.0)) << name << ": " << s90 << " x, stated " << stated;
    }
    // An unrelated cause (outside the effect's group) at most once per point, or a quarter of
    // its runs: a wrong name is worse than none.
    for (const Point& p : curve) EXPECT_LE(p.unrelated, std::max(1, p.runs / 4)) << name << " x" << p.multiple;
  }
  report::Figure figure;
  figure.title = "Audit detection probability, independent truths, 0.1 um / 1 mA, 1 s at 1.5 V";
  figure.axes = {axes};
  report::write_file_atomically(std::string(AMBID_BINARY_DIR) + "/audit_detection.svg", report::render_svg(figure));
}

}  // namespace audit_independent_slow_test
}  // namespace ambid::diag
