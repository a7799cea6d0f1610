#pragma once
// The fit of each identification method (identify_experiment.cpp), for the registry
// (methods.cpp). Each fits the part of a record identify_experiment hands it, after the
// registry's requirements were checked.
#include "core/experiment.hpp"
#include "core/model_file.hpp"
#include "identifier/identify_experiment.hpp"

namespace ambid::ident::detail {

void fit_deadbeat(const Experiment& fit, const IdentifyOptions& options, Model& model);
void fit_deadbeat_iv(const Experiment& fit, const IdentifyOptions& options, Model& model);
void fit_okid(const Experiment& fit, const IdentifyOptions& options, Model& model);
void fit_closed_loop(const Experiment& fit, const IdentifyOptions& options, Model& model);
void fit_projection(const Experiment& fit, const IdentifyOptions& options, Model& model);
void fit_pem(const Experiment& fit, const IdentifyOptions& options, Model& model);
// recursive_identification.cpp: the recursive estimator over the whole record.
void fit_rpem(const Experiment& fit, const IdentifyOptions& options, Model& model);
void fit_greybox(const Experiment& fit, const IdentifyOptions& options, Model& model);

}  // namespace ambid::ident::detail
