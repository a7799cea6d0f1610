#pragma once
// The maglev1coil_voltage family's linear structure at the operating point (the one
// maglev_identification.hpp writes), for the structured FRF fit of `ambid frf`
// (frequency_domain/frf_structured.hpp):
//   theta = [a, b, R_over_L, kw_over_L, emf],  states x, x', i,
//   A = [0 1 0; a 0 -b; 0 emf -R/L],  B = [0; 0; kw/L],  C = [1 0 0; 0 0 1],  D = 0,
// with a = n_x g / x0 and b = n_i g / i0 at the measured point (gravity balance). Both pairs
// x/u and i/u together determine all five. Derived: the unstable pole, the positive real
// eigenvalue of A (sqrt(a) without the back-EMF's coupling). a and b change with the gap: the
// structure is fitted per reference level, each at its own means (level signal x), and a level's
// theta carried to the operating point by gravity balance at both (a x, b i, emf i invariant).
#include <Eigen/Core>

#include "core/state_space.hpp"
#include "identifier/frequency_domain/frf_structured.hpp"

namespace ambid::ident {

// The linear model of theta (five entries, as above).
ContinuousSystem maglev_structure_model(const Eigen::VectorXd& theta);

// Start: the header's nominal parameters at its operating point x, i (the back-EMF constant
// closed by gravity balance like the force constant). Error naming a missing value.
const FrfStructure& maglev_frf_structure();

}  // namespace ambid::ident
