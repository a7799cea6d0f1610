#include "identifier/frequency_domain/frf_loop.hpp"

#include <algorithm>
#include <numbers>
#include <utility>

#include "core/error.hpp"
#include "core/linalg.hpp"
#include "identifier/frequency_domain/freq_response.hpp"

namespace ambid::ident {
namespace {

Eigen::Index index_of(const std::vector<std::string>& names, const std::string& name) {
  const auto it = std::find(names.begin(), names.end(), name);
  return it == names.end() ? -1 : static_cast<Eigen::Index>(it - names.begin());
}

}  // namespace

LoopResponse loop_response(const StateSpaceController& controller, const LoopSignalNames& signals, double omega) {
  const auto ny = static_cast<Eigen::Index>(signals.y.size());
  const auto nu = static_cast<Eigen::Index>(signals.u.size());
  const auto nr = static_cast<Eigen::Index>(signals.r.size());
  const auto no = static_cast<Eigen::Index>(controller.outputs.size());
  if (nr != 0 && nr != no)
    throw Error("loop response: " + std::to_string(nr) + " references for " + std::to_string(no) +
                " controller outputs (reference j is added to controller output j)");

  const Eigen::MatrixXcd Kc = freq_response(controller, omega);  // outputs x controller inputs
  Eigen::MatrixXcd P = Eigen::MatrixXcd::Zero(nu, no);
  for (Eigen::Index o = 0; o < no; ++o) {
    const Eigen::Index i = index_of(signals.u, controller.outputs[static_cast<std::size_t>(o)]);
    if (i < 0)
      throw Error("loop response: controller output '" + controller.outputs[static_cast<std::size_t>(o)] +
                  "' is not a plant input");
    P(i, o) = 1.0;
  }
  Eigen::MatrixXcd Ky = Eigen::MatrixXcd::Zero(no, ny), Ku = Eigen::MatrixXcd::Zero(no, nu),
                   Kr = Eigen::MatrixXcd::Zero(no, nr);
  for (std::size_t c = 0; c < controller.inputs.size(); ++c) {
    const std::string& name = controller.inputs[c];
    const auto col = static_cast<Eigen::Index>(c);
    if (const Eigen::Index i = index_of(signals.y, name); i >= 0) {
      Ky.col(i) += Kc.col(col);
    } else if (const Eigen::Index j = index_of(signals.u, name); j >= 0) {
      Ku.col(j) += Kc.col(col);
    } else if (const Eigen::Index k = index_of(signals.r, name); k >= 0) {
      Kr.col(k) += Kc.col(col);
    } else {
      throw Error("loop response: controller input '" + name + "' is not an output, input or reference of the loop");
    }
  }
  Eigen::MatrixXcd E = Eigen::MatrixXcd::Zero(nu, nr);
  if (nr != 0) E = P;
  const Eigen::MatrixXcd IminusPKu = Eigen::MatrixXcd::Identity(nu, nu) - P * Ku;
  linalg::RankedSolution<Eigen::MatrixXcd> K = linalg::qr_solve(IminusPKu, Eigen::MatrixXcd(P * Ky));
  if (K.rank < nu)
    throw Error("loop response: the controller's path from u back to u makes I - Ku singular at " +
                std::to_string(omega / (2.0 * std::numbers::pi)) + " Hz");
  LoopResponse out;
  out.K = std::move(K.x);
  out.M = linalg::qr_solve(IminusPKu, Eigen::MatrixXcd(P * Kr + E)).x;
  return out;
}

}  // namespace ambid::ident
