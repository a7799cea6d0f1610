#include "diagnostics/audit/audit_foils.hpp"

#include <cmath>

#include "core/error.hpp"

namespace ambid::diag {
namespace {

void scale_parameter(Experiment& header, const char* name, double relative) {
  const auto it = header.plant.parameters.find(name);
  if (it == header.plant.parameters.end()) throw Error(std::string("audit foil: the sidecar has no parameter ") + name);
  it->second *= 1.0 + relative;
}

const std::vector<Foil>& amb1dof_foils() {
  static const std::vector<Foil> foils = {
      {"Ls1 relative error", "1", 0.1, -0.5, 1.0, [](Experiment& h, double v) { scale_parameter(h, "Ls1", v); }},
      {"Ls2 relative error", "1", 0.1, -0.5, 1.0, [](Experiment& h, double v) { scale_parameter(h, "Ls2", v); }},
      {"position sensor offset", "m", 5e-6, -1e-4, 1e-4,
       [](Experiment& h, double v) { h.operating_point["x"] = h.operating_point.at("x") - v; }},
  };
  return foils;
}

}  // namespace

const std::vector<Foil>& audit_foils(const std::string& model) {
  static const std::vector<Foil> none;
  return model == "amb1dof_voltage" ? amb1dof_foils() : none;
}

std::vector<FoilFinding> fit_foils(const Experiment& measured, const Eigen::MatrixXd& measured_y,
                                   const std::vector<sim::Effect>& effects, const Eigen::MatrixXd& base_y,
                                   const Eigen::MatrixXd& rival_y, const Segment& estimation, const Segment& validation,
                                   Eigen::Index covariance_lags, const FitOptions& options) {
  std::vector<FoilFinding> out;
  for (const Foil& foil : audit_foils(measured.plant.model)) {
    auto replay = [&](double value, Eigen::Index samples) {
      Experiment header = measured;
      foil.apply(header, value);
      return replay_outputs(header, effects, samples);
    };
    // Start at whichever sign of the typical size replays closer.
    double start = 1.0, best = INFINITY;
    for (double s : {1.0, -1.0}) {
      try {
        const double cost = nrmse(measured_y, replay(s * foil.scale, estimation.end), estimation).squaredNorm();
        if (cost < best) best = cost, start = s;
      } catch (const InsufficientData&) {
        throw;
      } catch (const Error&) {
        continue;
      }
    }
    if (!std::isfinite(best)) continue;
    const ScaledFit fit = fit_scaled(
        measured_y, estimation, [&](const double* theta) { return replay(theta[0] * foil.scale, estimation.end); },
        Eigen::VectorXd::Constant(1, start), Eigen::VectorXd::Constant(1, foil.lower / foil.scale),
        Eigen::VectorXd::Constant(1, foil.upper / foil.scale), options);
    FoilFinding f{foil.name, foil.unit, fit.theta[0] * foil.scale, {}, {}, {}};
    Eigen::MatrixXd y;
    try {
      y = replay(f.value, measured_y.rows());
    } catch (const InsufficientData&) {
      throw;
    } catch (const Error&) {
      continue;
    }
    f.test = improvement_test(measured_y, base_y, y, validation, covariance_lags);
    f.rival_gain = improvement_test(measured_y, y, rival_y, validation, covariance_lags);
    f.nrmse_after = nrmse(measured_y, y, validation);
    out.push_back(std::move(f));
  }
  return out;
}

}  // namespace ambid::diag
