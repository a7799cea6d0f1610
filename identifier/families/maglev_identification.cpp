#include "identifier/families/maglev_identification.hpp"

#include <cmath>
#include <iomanip>
#include <sstream>

#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "identifier/families/maglev_frf_structure.hpp"
#include "identifier/families/maglev_greybox.hpp"

namespace ambid::ident {
namespace {

const std::string kMaglevWho = "identify (maglev1coil_voltage)";

double operating(const Experiment& e, const char* name) {
  const auto it = e.operating_point.find(name);
  if (it == e.operating_point.end()) throw Error(kMaglevWho + ": operating_point." + name + " is missing");
  return it->second;
}

}  // namespace

void fit_maglev_greybox_model(const Experiment& e, const IdentifyOptions&, Model& model) {
  if (e.y_names != std::vector<std::string>{"x", "i"} || e.u_names != std::vector<std::string>{"u"})
    throw Error(kMaglevWho + ": the grey-box fit needs signals y = [x, i] and u = [u]");
  MaglevGreyBoxInput in;
  in.sample_time = e.sample_time;
  in.x = e.y.col(0);
  in.i = e.y.col(1);
  in.u = e.u.col(0);
  in.x0 = operating(e, "x");
  in.i0 = operating(e, "i");
  in.nominal = e.plant.parameters;
  const MaglevGreyBoxFit fit = fit_maglev_greybox(in);
  const auto& v = fit.value;
  const auto nominal = [&](const char* name) { return e.plant.parameters.at(name); };  // checked by the fit
  const double kw = nominal("kw"), n_i = v.at("n_i"), n_x = v.at("n_x"), L = v.at("L"), R = v.at("R");
  // Back-EMF constant closed like the force constant: Ke' = Ke / rho (Km' = Km / rho at the point).
  const double Ke_closed = v.at("Ke") / v.at("rho");
  const double emf = n_i * Ke_closed * std::pow(in.i0, n_i - 1.0) / (std::pow(in.x0, n_x) * L);
  Eigen::VectorXd theta(5);
  theta << v.at("stiffness"), v.at("current_gain"), R / L, kw / L, emf;
  const ContinuousSystem c = maglev_structure_model(theta);
  model.continuous = c;
  model.discrete = c2d_zoh(c, e.sample_time);
  model.parameters = {
      {"a", v.at("stiffness")}, {"b", v.at("current_gain")}, {"R_over_L", R / L}, {"kw_over_L", kw / L}, {"emf", emf}};
  model.uncertainty["a"] = fit.sigma.at("stiffness");
  model.uncertainty["b"] = fit.sigma.at("current_gain");
  // The other structure parameters' sigmas by first-order propagation of the physical ones',
  // taken as independent (the fit gives no covariance between its two steps; R and L share
  // the coil regression's beta and err together, so the sigma of R/L is an upper bound).
  const auto& s = fit.sigma;
  const auto rel = [&](const char* name) { return s.at(name) / v.at(name); };
  model.uncertainty["R_over_L"] = R / L * std::hypot(rel("R"), rel("L"));
  model.uncertainty["kw_over_L"] = kw / L * rel("L");
  // emf = n_i Ke_at_point / (rho L): Ke at the point, not Ke, whose sigma holds the exponents'
  // share times ln x0 (counted twice here until 2026-12-03: 2-3x the emf's sigma).
  model.uncertainty["emf"] =
      emf * std::sqrt(std::pow(rel("Ke_at_point"), 2) + std::pow(rel("rho"), 2) + std::pow(rel("L"), 2));
  for (const char* name : {"R", "L", "Ke", "Ke_at_point", "Km", "n_i", "n_x", "rho", "unstable_pole"}) {
    model.physical[name] = v.at(name);
    model.uncertainty[name] = fit.sigma.at(name);
  }
  nlohmann::json& extra = model.extra.json();
  const double m = nominal("m"), g = nominal("g"), Km = nominal("Km"), n_i0 = nominal("n_i"), n_x0 = nominal("n_x");
  const double i_nominal = std::pow(m * g * std::pow(in.x0, n_x0) / Km, 1.0 / n_i0);
  const bool measured =
      e.extra.json().is_object() && e.extra.json().value("operating_point_source", std::string()) == "measured";
  extra["operating_point"] = {{"source", measured ? "measured" : "nominal"},
                              {"x", in.x0},
                              {"i", in.i0},
                              {"u", operating(e, "u")},
                              {"nominal_equilibrium_current", i_nominal},
                              {"nominal_equilibrium_input", nominal("R") * i_nominal / kw},
                              {"current_ratio", in.i0 / i_nominal}};
  extra["greybox"] = {{"window_samples", fit.window_samples},           {"coil_residual_rms", fit.coil_residual_rms},
                      {"body_residual_rms", fit.body_residual_rms},     {"iterations", fit.iterations},
                      {"coil_window_samples", fit.coil_window_samples}, {"taken_as_known", {"m", "g", "kw"}}};
  if (!fit.unsupported.empty()) {
    std::string list;
    for (const auto& name : fit.unsupported) list += (list.empty() ? "" : ", ") + name;
    extra["warnings"].push_back("the record does not support " + list + " (one sigma above half the value)");
  }
  if (!fit.unresolved.empty()) {
    std::ostringstream list;
    list << std::setprecision(2);
    for (const auto& name : fit.unresolved)
      list << (list.tellp() > 0 ? ", " : "") << name << " +-" << 300.0 * fit.sigma.at(name) / std::abs(v.at(name))
           << " %";
    extra["warnings"].push_back("the record pins " + list.str() + " (three sigma), not to " +
                                std::to_string(int(std::lround(100 * in.tolerance))) + " %");
  }
  extra["greybox"]["unresolved"] = fit.unresolved;
}

}  // namespace ambid::ident
