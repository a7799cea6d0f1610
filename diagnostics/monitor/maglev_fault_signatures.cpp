#include "diagnostics/maglev_fault_signatures.hpp"

#include <functional>
#include <map>
#include <string>

#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "identifier/identify_window.hpp"
#include "plant_sim/maglev_loop.hpp"
#include "plant_sim/maglev_parameters.hpp"
#include "plant_sim/maglev_rig.hpp"

namespace ambid::diag {
namespace maglev_fault_signatures {

constexpr const char* kFamily = "maglev1coil_voltage";

// The one list of the maglev's monitored parameters and their roles.
constexpr MonitoredParameter kMaglevRoles[] = {
    {"R", {"coil_resistance", std::nullopt, "coil resistance"}},
    {"L", {"magnetic_saturation", std::nullopt, "coil inductance"}},
    {"Km", {"force_factor", std::nullopt, "force constant (Km/m: or the body's mass)"}},
    {"n_i", {"force_law", std::nullopt, "force law current exponent"}},
    {"n_x", {"force_law", std::nullopt, "force law gap exponent"}},
};

// The PID settings of the board (maglev_rig.hpp) the sidecar's rig.settings hold; the sensor's
// and DAC's settings there describe that record's truth, not the loop, and are not taken.
constexpr const char* kLoopSettings[] = {"Kp",           "Ti",      "Td",      "integral_min",
                                         "integral_max", "pid_min", "pid_max", "v_ref"};

struct Loop {
  sim::MaglevParameters nominal;
  sim::MaglevRig rig;
  sim::MaglevRunOptions run;
};

Loop loop_of(const Experiment& header) {
  if (header.plant.model != kFamily)
    throw Error(std::string("fault signatures: plant model '") + header.plant.model + "' is not " + kFamily);
  const auto x0 = header.operating_point.find("x");
  if (x0 == header.operating_point.end())
    throw Error("fault signatures: the maglev record's operating_point has no x (the gap to run the loop at)");
  Loop loop{sim::MaglevParameters::from_map(header.plant.parameters), {}, {}};
  const nlohmann::json& extra = header.extra.json();
  if (extra.is_object() && extra.contains("rig") && extra["rig"].is_object() && extra["rig"].contains("settings")) {
    const nlohmann::json& settings = extra["rig"]["settings"];
    for (const char* name : kLoopSettings)
      if (settings.is_object() && settings.contains(name) && settings[name].is_number())
        loop.rig.set(name, settings[name].get<double>());
  }
  loop.rig.log_x = loop.rig.log_u = loop.rig.log_i = 0.0;
  loop.rig.validate();
  loop.run.name = "fault signature run";
  loop.run.sample_time = header.sample_time;
  loop.run.samples = Eigen::Index(12.0 / header.sample_time);
  const double x = x0->second;
  loop.run.levels = {x, x - 5e-4, x + 5e-4, x - 2.5e-4, x + 2.5e-4};
  loop.run.step_period = 1.5;
  loop.run.noise_amplitude = 0.5;
  loop.run.seed = 1;
  return loop;
}

// The monitored parameters the grey-box fit reads from the loop run with `truth` and `rig`.
std::map<std::string, double> identified(const Loop& loop, const sim::MaglevParameters& truth,
                                         const sim::MaglevRig& rig, const std::string& what) {
  const sim::MaglevRun run = sim::run_maglev_rig(truth, loop.nominal, rig, loop.run);
  if (!run.ended.empty()) throw Error("fault signatures: the loop with " + what + ": " + run.ended);
  ident::WindowIdentification id;
  try {
    id = ident::identify_window(run.experiment, ident::window_identify_options("greybox"));
  } catch (const Error& e) {
    throw Error("fault signatures: the loop with " + what + " is not identified: " + e.what());
  }
  std::map<std::string, double> out;
  for (const MonitoredParameter& p : kMaglevRoles)
    out[std::string(p.parameter)] = id.model.physical.at(std::string(p.parameter));
  return out;
}

}  // namespace maglev_fault_signatures

std::span<const MonitoredParameter> maglev_monitored_parameters() { return maglev_fault_signatures::kMaglevRoles; }

std::vector<FaultHypothesis> maglev_fault_hypotheses(const Experiment& header, const SignatureOptions& options) {
  using namespace maglev_fault_signatures;
  options.validate();
  const Loop loop = loop_of(header);
  const double h = options.relative_step;
  const auto base = identified(loop, loop.nominal, loop.rig, "the nominal plant");
  // A fault of relative size s applied to a copy of the truth and the rig.
  using Apply = std::function<void(sim::MaglevParameters&, sim::MaglevRig&, double)>;
  auto column = [&](const std::string& what, const Apply& apply) {
    sim::MaglevParameters up = loop.nominal, down = loop.nominal;
    sim::MaglevRig rig_up = loop.rig, rig_down = loop.rig;
    apply(up, rig_up, h);
    apply(down, rig_down, -h);
    const auto plus = identified(loop, up, rig_up, what + " +" + std::to_string(h));
    const auto minus = identified(loop, down, rig_down, what + " -" + std::to_string(h));
    std::map<std::string, double> s;
    for (const auto& [name, value] : base) s[name] = (plus.at(name) - minus.at(name)) / (2.0 * h * value);
    return s;
  };
  const double x0 = header.operating_point.at("x");
  return {
      {"coil_resistance",
       std::nullopt,
       "coil resistance",
       {"R"},
       column("R", [](auto& p, auto&, double s) { p.R *= 1.0 + s; })},
      {"amplifier_gain",
       std::nullopt,
       "amplifier gain (R, L alike: kw is taken as known)",
       {},
       column("kw", [](auto& p, auto&, double s) { p.kw *= 1.0 + s; })},
      {"magnetic_saturation",
       std::nullopt,
       "coil inductance",
       {"L"},
       column("L", [](auto& p, auto&, double s) { p.L *= 1.0 + s; })},
      {"force_factor",
       std::nullopt,
       "force constant (Km/m: or the body's mass)",
       {"Km"},
       column("Km", [](auto& p, auto&, double s) { p.Km *= 1.0 + s; })},
      {"sensor_gain",
       std::nullopt,
       "position sensor gain",
       {},
       column("sensor_gain", [](auto&, auto& r, double s) { r.sensor_gain *= 1.0 + s; })},
      {"sensor_offset",
       std::nullopt,
       "position sensor offset",
       {},
       column("sensor_offset", [x0](auto&, auto& r, double s) { r.sensor_offset += s * x0; })},
  };
}

const std::vector<FaultHypothesis>& default_maglev_fault_hypotheses() {
  static const std::vector<FaultHypothesis> hypotheses = [] {
    Experiment header;
    header.plant.model = maglev_fault_signatures::kFamily;
    header.plant.parameters = sim::MaglevParameters::nominal().to_map();
    header.sample_time = 3.25e-3;
    header.operating_point["x"] = 0.014;
    return maglev_fault_hypotheses(header);
  }();
  return hypotheses;
}

}  // namespace ambid::diag
