#include "identifier/families/physical_coordinates.hpp"

#include <cmath>
#include <limits>
#include <optional>
#include <sstream>
#include <string>

#include "core/error.hpp"
#include "core/linalg.hpp"

namespace ambid::ident {
namespace {

// Inverse of a square matrix with a rank check; `what` names it in the error.
Eigen::MatrixXd checked_inverse(const Eigen::MatrixXd& m, const std::string& what, double* condition = nullptr) {
  const std::optional<Eigen::MatrixXd> regular = linalg::regular_inverse(m);
  if (!regular)
    throw Error(what + " is singular (rank " + std::to_string(linalg::rank(m)) + " of " + std::to_string(m.rows()) +
                ")");
  const Eigen::MatrixXd& inv = *regular;
  const double cond = m.lpNorm<1>() * inv.lpNorm<1>();  // entrywise 1-norms: a cheap upper-bound estimate
  if (condition) *condition = cond;
  if (!(cond < 1.0 / (1e3 * std::numeric_limits<double>::epsilon()))) {
    std::ostringstream s;
    s.precision(3);
    s << what << " is numerically singular (condition estimate " << cond << ")";
    throw Error(s.str());
  }
  return inv;
}

}  // namespace

SecondOrderForm second_order_form(const ContinuousSystem& sys, const Eigen::MatrixXd& output_calibration) {
  sys.validate();
  const Eigen::Index n = sys.states(), p = sys.outputs(), m = sys.inputs();
  if (n != 2 * p)
    throw Error("second-order form needs twice as many states as outputs (half of the states measured), got " +
                std::to_string(n) + " states and " + std::to_string(p) + " outputs");
  Eigen::MatrixXd C = sys.C, D = sys.D;
  if (output_calibration.size() != 0) {
    if (output_calibration.rows() != p || output_calibration.cols() != p)
      throw Error("second-order form: output calibration is " + dims(output_calibration) + ", expected " +
                  std::to_string(p) + "x" + std::to_string(p));
    const Eigen::MatrixXd C1inv = checked_inverse(output_calibration, "second-order form: the output calibration C1");
    C = C1inv * C;
    D = C1inv * D;
  }
  Eigen::MatrixXd O(n, n);
  O << C, C * sys.A;
  SecondOrderForm out;
  const Eigen::MatrixXd P = checked_inverse(O, "second-order form: [C; C A]", &out.condition_number);
  out.transformation = P;
  out.system.A = O * sys.A * P;
  out.system.B = O * sys.B;
  out.system.C = C * P;
  out.system.D = D;
  out.stiffness = out.system.A.bottomLeftCorner(p, p);
  out.damping = out.system.A.bottomRightCorner(p, p);
  out.input = out.system.B.bottomRows(p);
  (void)m;
  return out;
}

SecondOrderForm second_order_form(const DiscreteSystem& sys, const Eigen::MatrixXd& output_calibration) {
  return second_order_form(d2c_zoh(sys), output_calibration);
}

DiscreteSystem to_measured_coordinates(const DiscreteSystem& sys, const Eigen::MatrixXd& true_C) {
  sys.validate();
  const Eigen::Index n = sys.states();
  if (true_C.rows() != n || true_C.cols() != n || sys.outputs() != n)
    throw Error("measured coordinates need a square true output matrix of the state dimension " + std::to_string(n) +
                " and as many outputs, got true C " + dims(true_C) + " and " + std::to_string(sys.outputs()) +
                " outputs");
  // x_phys = T z with T = true_C^-1 Chat.
  const Eigen::MatrixXd T = checked_inverse(true_C, "measured coordinates: the true C") * sys.C;
  const Eigen::MatrixXd Tinv = checked_inverse(T, "measured coordinates: the transformation true_C^-1 Chat");
  DiscreteSystem out;
  out.A = T * sys.A * Tinv;
  out.B = T * sys.B;
  out.C = sys.C * Tinv;
  out.D = sys.D;
  out.sample_time = sys.sample_time;
  return out;
}

}  // namespace ambid::ident
