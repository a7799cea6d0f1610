#include "identifier/time_domain/kalman_gain.hpp"

#include <string>

#include "core/error.hpp"

namespace ambid::ident {

KalmanGainEstimate kalman_gain_from_markov(const Eigen::MatrixXd& A, const Eigen::MatrixXd& C,
                                           const MarkovSequence& gain, Eigen::Index count,
                                           const LeastSquaresOptions& options) {
  const Eigen::Index n = A.rows(), p = C.rows();
  if (A.cols() != n || C.cols() != n || n < 1 || p < 1)
    throw Error("Kalman gain: inconsistent A " + std::to_string(A.rows()) + "x" + std::to_string(A.cols()) + " and C " +
                std::to_string(C.rows()) + "x" + std::to_string(C.cols()));
  const Eigen::Index J = static_cast<Eigen::Index>(gain.size()) - 1;
  if (count == 0) count = J;
  if (count < 1 || count > J)
    throw Error("Kalman gain: " + std::to_string(count) + " gain Markov parameters requested, " + std::to_string(J) +
                " available (N_1 .. N_J)");
  for (Eigen::Index k = 1; k <= count; ++k) {
    const Eigen::MatrixXd& N = gain[static_cast<std::size_t>(k)];
    if (N.rows() != p || N.cols() != p)
      throw Error("Kalman gain: gain Markov parameter " + std::to_string(k) + " is " + std::to_string(N.rows()) + "x" +
                  std::to_string(N.cols()) + ", expected " + std::to_string(p) + "x" + std::to_string(p));
  }
  Eigen::MatrixXd O(count * p, n), Z(count * p, p);
  Eigen::MatrixXd CAk = C;
  for (Eigen::Index k = 0; k < count; ++k) {
    O.middleRows(k * p, p) = CAk;
    Z.middleRows(k * p, p) = gain[static_cast<std::size_t>(k + 1)];
    CAk = CAk * A;
  }
  std::vector<std::string> names;
  for (Eigen::Index j = 0; j < n; ++j) names.push_back("state " + std::to_string(j + 1));
  KalmanGainEstimate out;
  {
    LeastSquaresAccumulator acc(n, p, names);
    acc.add(O, Z);
    out.fit = acc.solve(options);
    out.predictor_gain = out.fit.theta;
  }
  // (4.35): the same stack against [C A; ...; C A^count] gives K itself when A is invertible.
  const Eigen::MatrixXd OA = O * A;
  try {
    LeastSquaresAccumulator acc(n, p, names);
    acc.add(OA, Z);
    out.filter_gain = acc.solve(options).theta;
  } catch (const InsufficientData&) {
    out.filter_gain.resize(0, 0);  // A singular: K is not determined, AK is
  }
  return out;
}

}  // namespace ambid::ident
