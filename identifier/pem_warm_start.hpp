#pragma once
// A previous `pem` fit to start the next window from (IdentifyOptions::pem_warm_start): its
// v1..v9, the constant terms w and the predictor gain K; the initial state is re-estimated.
// From a start this close the prediction-error method converges in a few iterations instead
// of refining the least-squares starts (amb1dof_prediction_error.hpp in identifier/families).
#include <Eigen/Core>

#include "core/model_file.hpp"

namespace ambid::ident {

struct PemWarmStart {
  Eigen::Matrix<double, 9, 1> v = Eigen::Matrix<double, 9, 1>::Zero();               // v1..v9
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();                                  // w of the x'', i1', i2' rows
  Eigen::Matrix<double, 4, 3> predictor_gain = Eigen::Matrix<double, 4, 3>::Zero();  // K
};

// The start a `pem` model carries: model.parameters v1..v9, model.extra["pem"]["offset"] (3)
// and ["predictor_gain"] (4 rows of 3). Throws Error naming what is missing or malformed
// (e.g. a model of another method).
PemWarmStart pem_warm_start(const Model& previous);

}  // namespace ambid::ident
