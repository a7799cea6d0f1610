#include "identifier/time_domain/arx.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.hpp"

namespace ambid::ident {
namespace {

Eigen::Index regressor_count(Eigen::Index p, Eigen::Index m, Eigen::Index q, bool direct) {
  return (direct ? m : 0) + (p + m) * q;
}

std::vector<std::string> regressor_names(Eigen::Index p, Eigen::Index m, Eigen::Index q, bool direct,
                                         const std::string& ys, const std::string& us) {
  std::vector<std::string> names;
  if (direct)
    for (Eigen::Index c = 0; c < m; ++c) names.push_back(us + std::to_string(c + 1) + "[k]");
  for (Eigen::Index i = 1; i <= q; ++i) {
    for (Eigen::Index c = 0; c < p; ++c) names.push_back(ys + std::to_string(c + 1) + "[k-" + std::to_string(i) + "]");
    for (Eigen::Index c = 0; c < m; ++c) names.push_back(us + std::to_string(c + 1) + "[k-" + std::to_string(i) + "]");
  }
  return names;
}

// Regressor row for sample k (k >= q) into `row`.
void fill_row(const Eigen::MatrixXd& y, const Eigen::MatrixXd& u, Eigen::Index q, bool direct, Eigen::Index k,
              Eigen::Ref<Eigen::RowVectorXd, 0, Eigen::InnerStride<>> row) {
  const Eigen::Index p = y.cols(), m = u.cols();
  Eigen::Index c = 0;
  if (direct) {
    row.segment(c, m) = u.row(k);
    c += m;
  }
  for (Eigen::Index i = 1; i <= q; ++i) {
    row.segment(c, p) = y.row(k - i);
    c += p;
    row.segment(c, m) = u.row(k - i);
    c += m;
  }
}

void check_inputs(const Eigen::MatrixXd& z, const Eigen::MatrixXd& y, const Eigen::MatrixXd& u,
                  const ArxOptions& options) {
  if (options.order < 1) throw Error("ARX: order must be >= 1, got " + std::to_string(options.order));
  if (y.cols() < 1) throw Error("ARX: y needs at least one channel, got " + dims(y));
  if (z.cols() < 1) throw Error("ARX: the target needs at least one channel, got " + dims(z));
  if (u.rows() != y.rows() || z.rows() != y.rows())
    throw Error("ARX: signals must have the same number of samples: target " + dims(z) + ", y " + dims(y) + ", u " +
                dims(u));
  if (options.direct_term && u.cols() == 0) throw Error("ARX: direct_term needs at least one input channel");
  if (!y.allFinite() || !u.allFinite() || !z.allFinite()) throw Error("ARX: non-finite sample in the data");
  const Eigen::Index n = y.rows(), q = options.order;
  const Eigen::Index regs = regressor_count(y.cols(), u.cols(), q, options.direct_term);
  if (n - q <= regs)
    throw InsufficientData("ARX: order " + std::to_string(q) + " with " + std::to_string(y.cols()) + " outputs and " +
                           std::to_string(u.cols()) + " inputs has " + std::to_string(regs) +
                           " regressors and needs more than " + std::to_string(regs + q) + " samples, got " +
                           std::to_string(n));
}

}  // namespace

Eigen::Index ArxModel::a_regressor(Eigen::Index i, Eigen::Index channel) const {
  if (i < 1 || i > order || channel < 0 || channel >= outputs)
    throw Error("ARX: no coefficient a_" + std::to_string(i) + " channel " + std::to_string(channel));
  return (direct_term ? inputs : 0) + (i - 1) * (outputs + inputs) + channel;
}

Eigen::Index ArxModel::b_regressor(Eigen::Index i, Eigen::Index channel) const {
  if (i < 0 || i > order || channel < 0 || channel >= inputs || (i == 0 && !direct_term))
    throw Error("ARX: no coefficient b_" + std::to_string(i) + " channel " + std::to_string(channel));
  if (i == 0) return channel;
  return (direct_term ? inputs : 0) + (i - 1) * (outputs + inputs) + outputs + channel;
}

Eigen::MatrixXd ArxModel::a_standard_deviation(Eigen::Index i) const {
  Eigen::MatrixXd s(targets, outputs);
  for (Eigen::Index r = 0; r < targets; ++r)
    for (Eigen::Index c = 0; c < outputs; ++c) {
      const Eigen::Index j = a_regressor(i, c);
      s(r, c) = std::sqrt(std::max(0.0, fit.covariance(j, r, j, r)));
    }
  return s;
}

Eigen::MatrixXd ArxModel::b_standard_deviation(Eigen::Index i) const {
  Eigen::MatrixXd s = Eigen::MatrixXd::Zero(targets, inputs);
  if (i == 0 && !direct_term) return s;
  for (Eigen::Index r = 0; r < targets; ++r)
    for (Eigen::Index c = 0; c < inputs; ++c) {
      const Eigen::Index j = b_regressor(i, c);
      s(r, c) = std::sqrt(std::max(0.0, fit.covariance(j, r, j, r)));
    }
  return s;
}

double ArxModel::covariance(Eigen::Index r1, Eigen::Index j1, Eigen::Index r2, Eigen::Index j2) const {
  return fit.covariance(j1, r1, j2, r2);
}

ArxModel fit_arx(const Eigen::MatrixXd& z, const Eigen::MatrixXd& y, const Eigen::MatrixXd& u,
                 const ArxOptions& options) {
  check_inputs(z, y, u, options);
  const Eigen::Index p = y.cols(), m = u.cols(), t = z.cols(), q = options.order, n = y.rows();
  const bool direct = options.direct_term;
  const Eigen::Index regs = regressor_count(p, m, q, direct);
  LeastSquaresAccumulator acc(regs, t, regressor_names(p, m, q, direct, options.output_symbol, options.input_symbol));
  const Eigen::Index block = 512;
  Eigen::MatrixXd phi(block, regs), target(block, t);
  std::vector<bool> across_break(std::size_t(n), false);  // the window k-q .. k holds a break
  for (const Eigen::Index b : options.breaks)
    for (Eigen::Index k = std::max<Eigen::Index>(b, 0); k < std::min(n, b + q); ++k)
      across_break[std::size_t(k)] = true;
  for (Eigen::Index k0 = q; k0 < n; k0 += block) {
    const Eigen::Index end = std::min(n, k0 + block);
    Eigen::Index rows = 0;
    for (Eigen::Index k = k0; k < end; ++k) {
      if (across_break[std::size_t(k)]) continue;
      fill_row(y, u, q, direct, k, phi.row(rows));
      target.row(rows) = z.row(k);
      ++rows;
    }
    if (rows > 0) acc.add(phi.topRows(rows), target.topRows(rows));
  }

  ArxModel model;
  model.order = q;
  model.direct_term = direct;
  model.outputs = p;
  model.inputs = m;
  model.targets = t;
  model.fit = acc.solve(options.least_squares);
  const Eigen::MatrixXd thetaT = model.fit.theta.transpose();  // targets x regressors
  model.b.push_back(direct ? Eigen::MatrixXd(thetaT.leftCols(m)) : Eigen::MatrixXd::Zero(t, m));
  Eigen::Index c = direct ? m : 0;
  for (Eigen::Index i = 1; i <= q; ++i) {
    model.a.push_back(thetaT.middleCols(c, p));
    c += p;
    model.b.push_back(thetaT.middleCols(c, m));
    c += m;
  }
  return model;
}

ArxModel fit_arx(const Eigen::MatrixXd& y, const Eigen::MatrixXd& u, const ArxOptions& options) {
  return fit_arx(y, y, u, options);
}

Eigen::MatrixXd arx_residuals(const ArxModel& model, const Eigen::MatrixXd& z, const Eigen::MatrixXd& y,
                              const Eigen::MatrixXd& u) {
  if (y.cols() != model.outputs || u.cols() != model.inputs || z.cols() != model.targets || y.rows() != u.rows() ||
      z.rows() != y.rows())
    throw Error("ARX residuals: data " + dims(z) + ", " + dims(y) + ", " + dims(u) + " do not fit the model");
  const Eigen::Index q = model.order;
  if (y.rows() <= q) throw InsufficientData("ARX residuals: need more than " + std::to_string(q) + " samples");
  Eigen::MatrixXd e(y.rows() - q, model.targets);
  for (Eigen::Index k = q; k < y.rows(); ++k) {
    Eigen::VectorXd pred = model.b[0] * u.row(k).transpose();
    for (Eigen::Index i = 1; i <= q; ++i)
      pred += model.a[static_cast<std::size_t>(i - 1)] * y.row(k - i).transpose() +
              model.b[static_cast<std::size_t>(i)] * u.row(k - i).transpose();
    e.row(k - q) = z.row(k) - pred.transpose();
  }
  return e;
}

}  // namespace ambid::ident
