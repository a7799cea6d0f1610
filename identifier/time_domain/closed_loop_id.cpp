#include "identifier/time_domain/closed_loop_id.hpp"

#include <algorithm>
#include <string>

#include "core/error.hpp"
#include "core/linalg.hpp"
#include "identifier/time_domain/kalman_gain.hpp"

namespace ambid::ident {
namespace {

using Index = Eigen::Index;

Index find(const std::vector<std::string>& names, const std::string& name) {
  const auto it = std::find(names.begin(), names.end(), name);
  return it == names.end() ? -1 : static_cast<Index>(it - names.begin());
}

}  // namespace

KnownController known_controller(const StateSpaceController& c, const std::vector<std::string>& u_names,
                                 const std::vector<std::string>& y_names) {
  const Index l = c.A.rows(), m = static_cast<Index>(u_names.size()), p = static_cast<Index>(y_names.size());
  const Index ni = static_cast<Index>(c.inputs.size()), no = static_cast<Index>(c.outputs.size());
  if (c.A.cols() != l || c.B.rows() != l || c.B.cols() != ni || c.C.rows() != no || c.C.cols() != l ||
      c.D.rows() != no || c.D.cols() != ni)
    throw Error("known controller: matrices A " + dims(c.A) + ", B " + dims(c.B) + ", C " + dims(c.C) + ", D " +
                dims(c.D) + " do not fit " + std::to_string(ni) + " inputs and " + std::to_string(no) + " outputs");
  KnownController k;
  k.A = c.A;
  k.B = Eigen::MatrixXd::Zero(l, m + p);
  k.C = Eigen::MatrixXd::Zero(m, l);
  k.D = Eigen::MatrixXd::Zero(m, m + p);
  std::vector<Index> column(static_cast<std::size_t>(ni));
  for (Index j = 0; j < ni; ++j) {
    const std::string& name = c.inputs[static_cast<std::size_t>(j)];
    Index idx = find(u_names, name);
    if (idx < 0) {
      idx = find(y_names, name);
      if (idx < 0)
        throw Error("known controller: controller input '" + name + "' is neither a plant input nor a plant output");
      idx += m;
    }
    column[static_cast<std::size_t>(j)] = idx;
    k.B.col(idx) += c.B.col(j);
  }
  for (Index i = 0; i < no; ++i) {
    const std::string& name = c.outputs[static_cast<std::size_t>(i)];
    const Index row = find(u_names, name);
    if (row < 0) throw Error("known controller: controller output '" + name + "' is not a plant input");
    k.C.row(row) += c.C.row(i);
    for (Index j = 0; j < ni; ++j) k.D(row, column[static_cast<std::size_t>(j)]) += c.D(i, j);
  }
  for (Index j = 0; j < m; ++j)
    if (k.D.col(j).norm() != 0.0)
      throw Error("known controller: direct feedthrough from plant input '" + u_names[static_cast<std::size_t>(j)] +
                  "' (non-zero D column): an algebraic loop through u is refused");
  return k;
}

ClosedLoopIdResult identify_with_known_controller(const Eigen::MatrixXd& r, const Eigen::MatrixXd& y,
                                                  const KnownController& controller,
                                                  const KnownControllerIdOptions& options) {
  const Index m = r.cols(), p = y.cols(), l = controller.A.rows();
  if (r.rows() != y.rows()) throw Error("known-controller CLID: r is " + dims(r) + " but y is " + dims(y));
  if (m < 1 || p < 1) throw Error("known-controller CLID: needs at least one excitation and one output channel");
  if (controller.A.cols() != l || controller.B.rows() != l || controller.B.cols() != m + p ||
      controller.C.rows() != m || controller.C.cols() != l || controller.D.rows() != m || controller.D.cols() != m + p)
    throw Error("known-controller CLID: controller A " + dims(controller.A) + ", B " + dims(controller.B) + ", C " +
                dims(controller.C) + ", D " + dims(controller.D) + " does not read [u (" + std::to_string(m) +
                "); y (" + std::to_string(p) + ")] and drive " + std::to_string(m) + " plant inputs");
  if (options.arx_order < 1)
    throw Error("known-controller CLID: arx_order must be >= 1, got " + std::to_string(options.arx_order));
  if (options.markov_count < 2)
    throw Error("known-controller CLID: markov_count must be >= 2, got " + std::to_string(options.markov_count));
  if (!(options.sample_time > 0.0)) throw Error("known-controller CLID: sample_time must be positive");

  ClosedLoopIdResult out;
  const ControllerMarkov cm = controller_markov(controller.A, controller.B, controller.C, controller.D, m,
                                                options.markov_count);  // refuses feedthrough from u
  out.controller_spectral_radius = linalg::spectral_radius(controller.A + controller.B.leftCols(m) * controller.C);

  ArxOptions arx_options;
  arx_options.order = options.arx_order;
  arx_options.direct_term = false;
  arx_options.least_squares = options.least_squares;
  arx_options.input_symbol = "r";
  arx_options.breaks = options.breaks;
  out.arx = fit_arx(y, r, arx_options);
  out.closed_loop = markov_from_arx(out.arx, options.markov_count);
  out.open_loop = open_loop_markov(out.closed_loop, cm);

  const EraResult e = era(out.open_loop.system, options.sample_time, options.era);
  out.plant = e.system;
  out.plant.D = Eigen::MatrixXd::Zero(p, m);
  out.hankel_singular_values = e.hankel_singular_values;
  out.suggested_order = e.suggested_order;

  const Index n = out.plant.states();
  Index count = options.kalman_count;
  if (count == 0) count = std::min<Index>(options.markov_count, (2 * n + p - 1) / p + 1);
  const KalmanGainEstimate k =
      kalman_gain_from_markov(out.plant.A, out.plant.C, out.open_loop.gain, count, options.least_squares);
  out.predictor_gain = k.predictor_gain;
  out.filter_gain = k.filter_gain;
  return out;
}

}  // namespace ambid::ident
