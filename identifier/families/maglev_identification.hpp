#pragma once
// The maglev1coil_voltage family's identification (plant_families.hpp, method greybox): the
// grey-box fit of maglev_greybox.hpp on an experiment, written as a model.json.
//   parameters (structure, at the operating point): a = n_x g / x0, b = n_i g / i0,
//     R_over_L, kw_over_L, emf = n_i Ke' i0^(n_i-1) / (x0^n_x L)
//   continuous: states x, x', i; A = [0 1 0; a 0 -b; 0 emf -R/L], B = [0; 0; kw/L],
//     C = [1 0 0; 0 0 1] (the linearisation at the operating point, force constant closed by
//     gravity balance there: Ke' = Ke Km'/Km); discrete: its zero-order hold.
//   physical: R, L, Ke, Ke_at_point (Ke i0^(n_i-1) / x0^n_x), Km, n_i, n_x, rho (gravity balance
//     of the fitted law at the operating point), unstable_pole; uncertainty one sigma of every
//     parameter and physical quantity (of R_over_L, kw_over_L and emf propagated from the
//     physical ones, taken as independent).
//   extra.greybox.unresolved and a warning: the physical quantities whose three sigmas exceed
//     1 % of their value (on the rig's records Ke and Ke_at_point: maglev_greybox.hpp).
//   extra.operating_point: the source (measured or nominal), x0, i0, u0, and the nominal model's
//     own equilibrium current and command at x0 with the measured point's ratio to them.
#include "core/experiment.hpp"
#include "core/model_file.hpp"

namespace ambid::ident {

struct IdentifyOptions;

// Error for an experiment whose signals are not y = [x, i], u = [u], or whose nominal
// parameters or operating point lack a value; InsufficientData as fit_maglev_greybox.
void fit_maglev_greybox_model(const Experiment& experiment, const IdentifyOptions& options, Model& model);

}  // namespace ambid::ident
