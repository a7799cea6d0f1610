#include "identifier/time_domain/least_squares.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>
#include <utility>

#include "core/error.hpp"
#include "core/linalg.hpp"

namespace ambid::ident {
namespace {

std::string three_digits(double v) {
  std::ostringstream s;
  s.precision(3);
  s << v;
  return s.str();
}

// Upper-triangular factor of `m` (any shape), padded with zero rows to cols x cols.
Eigen::MatrixXd triangular_factor(const Eigen::MatrixXd& m) {
  const Eigen::Index k = m.cols();
  Eigen::MatrixXd r = Eigen::MatrixXd::Zero(k, k);
  if (m.rows() == 0) return r;
  r.topRows(std::min(m.rows(), k)) = linalg::qr_r(m);
  return r;
}

// "name (weight), ..." for the regressors that carry most of the given directions of V.
std::string involved_regressors(const Eigen::MatrixXd& V, Eigen::Index first, Eigen::Index last,
                                const std::vector<std::string>& names) {
  const Eigen::Index p = V.rows();
  Eigen::VectorXd weight = Eigen::VectorXd::Zero(p);
  for (Eigen::Index c = first; c < last; ++c) weight += V.col(c).cwiseAbs2();
  weight /= static_cast<double>(last - first);
  std::vector<Eigen::Index> order(static_cast<std::size_t>(p));
  std::iota(order.begin(), order.end(), Eigen::Index{0});
  std::sort(order.begin(), order.end(), [&](Eigen::Index a, Eigen::Index b) { return weight(a) > weight(b); });
  std::ostringstream s;
  const double cut = 0.02 * weight.maxCoeff();
  int listed = 0;
  for (const Eigen::Index j : order) {
    if (weight(j) < cut || listed == 8) break;
    if (listed++) s << ", ";
    s << names[static_cast<std::size_t>(j)] << " (" << three_digits(weight(j)) << ")";
  }
  return s.str();
}

}  // namespace

Eigen::MatrixXd LeastSquaresSolution::parameter_covariance(Eigen::Index target) const {
  if (target < 0 || target >= residual_covariance.rows())
    throw Error("least squares: target index " + std::to_string(target) + " out of range [0, " +
                std::to_string(residual_covariance.rows()) + ")");
  return residual_covariance(target, target) * inverse_gram;
}

double LeastSquaresSolution::covariance(Eigen::Index i, Eigen::Index j, Eigen::Index k, Eigen::Index l) const {
  return residual_covariance(j, l) * inverse_gram(i, k);
}

Eigen::MatrixXd LeastSquaresSolution::standard_deviations() const {
  const Eigen::VectorXd g = inverse_gram.diagonal().cwiseMax(0.0);
  const Eigen::VectorXd s = residual_covariance.diagonal().cwiseMax(0.0);
  return (g * s.transpose()).cwiseSqrt();
}

LeastSquaresAccumulator::LeastSquaresAccumulator(Eigen::Index regressors, Eigen::Index targets,
                                                 std::vector<std::string> regressor_names)
    : regressors_(regressors), targets_(targets), names_(std::move(regressor_names)) {
  if (regressors < 1 || targets < 1)
    throw Error("least squares needs at least one regressor and one target, got " + std::to_string(regressors) +
                " and " + std::to_string(targets));
  if (names_.empty()) {
    for (Eigen::Index j = 0; j < regressors; ++j) names_.push_back("regressor " + std::to_string(j));
  } else if (static_cast<Eigen::Index>(names_.size()) != regressors) {
    throw Error("least squares: " + std::to_string(names_.size()) + " regressor names for " +
                std::to_string(regressors) + " regressors");
  }
  const Eigen::Index k = regressors + targets;
  R_ = Eigen::MatrixXd::Zero(k, k);
  buffer_.resize(std::max<Eigen::Index>(256, 2 * k), k);
}

void LeastSquaresAccumulator::compress(const Eigen::MatrixXd& block) {
  const Eigen::Index k = regressors_ + targets_;
  Eigen::MatrixXd stacked(k + block.rows(), k);
  stacked << R_, block;
  R_ = triangular_factor(stacked);
}

void LeastSquaresAccumulator::flush_buffer() {
  if (buffered_ == 0) return;
  compress(buffer_.topRows(buffered_));
  buffered_ = 0;
}

void LeastSquaresAccumulator::add(const Eigen::Ref<const Eigen::MatrixXd>& phi,
                                  const Eigen::Ref<const Eigen::MatrixXd>& z) {
  if (phi.cols() != regressors_ || z.cols() != targets_ || phi.rows() != z.rows())
    throw Error("least squares: block of " + std::to_string(phi.rows()) + "x" + std::to_string(phi.cols()) +
                " regressors and " + std::to_string(z.rows()) + "x" + std::to_string(z.cols()) +
                " targets does not fit " + std::to_string(regressors_) + " regressors and " + std::to_string(targets_) +
                " targets");
  for (Eigen::Index i = 0; i < phi.rows(); ++i) {
    if (!phi.row(i).allFinite() || !z.row(i).allFinite())
      throw Error("least squares: non-finite value in data row " + std::to_string(rows_ + i));
  }
  Eigen::Index done = 0;
  while (done < phi.rows()) {
    const Eigen::Index take = std::min(phi.rows() - done, buffer_.rows() - buffered_);
    buffer_.block(buffered_, 0, take, regressors_) = phi.middleRows(done, take);
    buffer_.block(buffered_, regressors_, take, targets_) = z.middleRows(done, take);
    buffered_ += take;
    done += take;
    if (buffered_ == buffer_.rows()) flush_buffer();
  }
  rows_ += phi.rows();
}

Eigen::MatrixXd LeastSquaresAccumulator::factor() const {
  if (buffered_ == 0) return R_;
  const Eigen::Index k = regressors_ + targets_;
  Eigen::MatrixXd stacked(k + buffered_, k);
  stacked << R_, buffer_.topRows(buffered_);
  return triangular_factor(stacked);
}

LeastSquaresSolution LeastSquaresAccumulator::solve(const LeastSquaresOptions& options) const {
  const Eigen::Index p = regressors_, t = targets_;
  if (!(options.regularization >= 0.0) || !std::isfinite(options.regularization))
    throw Error("least squares: regularization must be >= 0 and finite, got " + three_digits(options.regularization));
  if (!(options.max_condition > 1.0))
    throw Error("least squares: max_condition must be > 1, got " + three_digits(options.max_condition));
  if (!(options.rank_tolerance < 1.0) || std::isnan(options.rank_tolerance))
    throw Error("least squares: rank_tolerance must be < 1, got " + three_digits(options.rank_tolerance));
  if (rows_ <= p)
    throw InsufficientData("least squares: " + std::to_string(rows_) + " data rows for " + std::to_string(p) +
                           " regressors; at least " + std::to_string(p + 1) +
                           " rows are needed (more data, or fewer regressors)");

  const Eigen::MatrixXd R = factor();
  const Eigen::MatrixXd R11 = R.topLeftCorner(p, p);
  const Eigen::MatrixXd R12 = R.topRightCorner(p, t);
  const Eigen::MatrixXd R22 = R.bottomRightCorner(t, t);

  LeastSquaresSolution out;
  out.rows = rows_;
  out.degrees_of_freedom = rows_ - p;
  out.column_norms.resize(p);
  for (Eigen::Index j = 0; j < p; ++j) {
    out.column_norms(j) = R11.col(j).norm();
    if (!(out.column_norms(j) > 0.0))
      throw InsufficientData("least squares: regressor " + names_[static_cast<std::size_t>(j)] +
                             " is identically zero over all " + std::to_string(rows_) +
                             " rows (that signal carries no excitation)");
  }

  // Regularised factor [S11 S12] of [R11 R12; sqrt(lambda) I 0].
  Eigen::MatrixXd S11 = R11, S12 = R12;
  const bool regularised = options.regularization > 0.0;
  if (regularised) {
    Eigen::MatrixXd aug = Eigen::MatrixXd::Zero(2 * p, p + t);
    aug.topLeftCorner(p, p) = R11;
    aug.topRightCorner(p, t) = R12;
    aug.bottomLeftCorner(p, p) = std::sqrt(options.regularization) * Eigen::MatrixXd::Identity(p, p);
    const Eigen::MatrixXd S = triangular_factor(aug);
    S11 = S.topLeftCorner(p, p);
    S12 = S.topRightCorner(p, t);
  }

  // Rank and condition of the column-equilibrated factor.
  Eigen::VectorXd scale(p);
  for (Eigen::Index j = 0; j < p; ++j) scale(j) = 1.0 / S11.col(j).norm();
  const Eigen::MatrixXd Se = S11 * scale.asDiagonal();
  const linalg::Svd svd = linalg::svd(Se);
  out.singular_values = svd.S;
  const double tol = options.rank_tolerance > 0.0
                         ? options.rank_tolerance
                         : static_cast<double>(std::max(rows_, p)) * std::numeric_limits<double>::epsilon();
  const double smax = out.singular_values(0);
  out.rank = 0;
  for (Eigen::Index i = 0; i < p; ++i)
    if (out.singular_values(i) > tol * smax) ++out.rank;
  if (out.rank < p) {
    const Eigen::Index missing = p - out.rank;
    throw InsufficientData("least squares: the regressors are rank deficient: numerical rank " +
                           std::to_string(out.rank) + " of " + std::to_string(p) + " (" + std::to_string(missing) +
                           (missing == 1 ? " direction" : " directions") + " without excitation, relative tolerance " +
                           three_digits(tol) + "); the missing directions involve " +
                           involved_regressors(svd.V, out.rank, p, names_) +
                           " (more exciting data, a lower model order, or regularization)");
  }
  out.condition_number = smax / out.singular_values(p - 1);
  if (!(out.condition_number <= options.max_condition))
    throw InsufficientData("least squares: the regressors are ill-conditioned: condition number " +
                           three_digits(out.condition_number) + " (column-equilibrated) exceeds the limit " +
                           three_digits(options.max_condition) + "; the weakest direction involves " +
                           involved_regressors(svd.V, p - 1, p, names_) +
                           " (more exciting data, a lower model order, or regularization)");
  out.raw_condition_number = linalg::condition_number(S11);

  const auto S11u = S11.triangularView<Eigen::Upper>();
  out.theta = S11u.solve(S12);
  const Eigen::MatrixXd misfit = R12 - R11.triangularView<Eigen::Upper>() * out.theta;
  out.residual_gram = misfit.transpose() * misfit + R22.transpose() * R22;  // R22 is triangular
  out.residual_covariance = out.residual_gram / static_cast<double>(out.degrees_of_freedom);
  const Eigen::MatrixXd Sinv = S11u.solve(Eigen::MatrixXd::Identity(p, p));
  const Eigen::MatrixXd SinvSinvT = Sinv * Sinv.transpose();
  if (regularised) {
    const Eigen::MatrixXd W = R11.triangularView<Eigen::Upper>() * SinvSinvT;
    out.inverse_gram = W.transpose() * W;
  } else {
    out.inverse_gram = SinvSinvT;
  }
  return out;
}

LeastSquaresSolution solve_least_squares(const Eigen::MatrixXd& phi, const Eigen::MatrixXd& z,
                                         const LeastSquaresOptions& options, std::vector<std::string> regressor_names) {
  LeastSquaresAccumulator acc(phi.cols(), z.cols(), std::move(regressor_names));
  acc.add(phi, z);
  return acc.solve(options);
}

}  // namespace ambid::ident
