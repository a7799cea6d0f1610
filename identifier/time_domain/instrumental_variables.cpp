#include "identifier/time_domain/instrumental_variables.hpp"

#include "core/error.hpp"
#include "core/linalg.hpp"

namespace ambid::ident {

LeastSquaresSolution solve_instrumental_variables(const Eigen::MatrixXd& phi, const Eigen::MatrixXd& z,
                                                  const Eigen::MatrixXd& instruments,
                                                  const std::vector<std::string>& names,
                                                  const LeastSquaresOptions& options) {
  const Eigen::Index rows = phi.rows(), p = phi.cols(), t = z.cols(), w = instruments.cols();
  if (z.rows() != rows || instruments.rows() != rows || static_cast<Eigen::Index>(names.size()) != p)
    throw Error(
        "instrumental variables: phi, z and the instruments must have the same rows and every regressor a name");
  if (w < p)
    throw InsufficientData("instrumental variables: " + std::to_string(w) + " instruments for " + std::to_string(p) +
                           " regressors; at least as many instruments as regressors are needed");
  if (rows <= w)
    throw InsufficientData("instrumental variables: " + std::to_string(rows) + " rows for " + std::to_string(w) +
                           " instruments; more rows are needed");
  std::vector<std::string> instrument_names;
  for (Eigen::Index j = 0; j < w; ++j) instrument_names.push_back("instrument " + std::to_string(j + 1));
  // Stage one: Q_w' [Phi Z] from the QR factor of [W | Phi | Z].
  LeastSquaresAccumulator projection(w, p + t, instrument_names);
  Eigen::MatrixXd block(rows, p + t);
  block << phi, z;
  projection.add(instruments, block);
  const Eigen::MatrixXd top = projection.factor().topRows(w);  // w x (w + p + t)
  // Q_w spans the instruments only when R_ww is regular (the columns of W independent).
  const Eigen::MatrixXd Rww = top.leftCols(w);
  Eigen::VectorXd scale(w);
  for (Eigen::Index j = 0; j < w; ++j) scale(j) = Rww.col(j).norm() > 0.0 ? 1.0 / Rww.col(j).norm() : 0.0;
  const Eigen::VectorXd sv = linalg::singular_values(Eigen::MatrixXd(Rww * scale.asDiagonal()));
  if (!(sv(w - 1) > 1e-10 * sv(0)))
    throw InsufficientData(
        "instrumental variables: the instruments are linearly dependent or zero (reciprocal "
        "condition " +
        std::to_string(sv(w - 1) / sv(0)) + "): they cannot separate the regressors");
  // Stage two: least squares on the projected equations.
  LeastSquaresAccumulator projected(p, t, names);
  projected.add(top.middleCols(w, p), top.rightCols(t));
  LeastSquaresSolution out = projected.solve(options);
  const Eigen::MatrixXd residual = z - phi * out.theta;
  out.rows = rows;
  out.degrees_of_freedom = rows - p;
  out.residual_gram = residual.transpose() * residual;
  out.residual_covariance = out.residual_gram / static_cast<double>(out.degrees_of_freedom);
  return out;
}

}  // namespace ambid::ident
