#include "identifier/time_domain/era.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <utility>

#include "core/error.hpp"
#include "core/linalg.hpp"

namespace ambid::ident {
namespace {

using Index = Eigen::Index;

std::string num(double v) {
  std::ostringstream s;
  s.precision(3);
  s << v;
  return s.str();
}

// [ Y_(1+shift+i+j) ] for i < r, j < s.
Eigen::MatrixXd hankel(const MarkovSequence& y, Index r, Index s, Index shift) {
  const Index p = y[0].rows(), m = y[0].cols();
  Eigen::MatrixXd h(p * r, m * s);
  for (Index i = 0; i < r; ++i)
    for (Index j = 0; j < s; ++j) h.block(i * p, j * m, p, m) = y[static_cast<std::size_t>(1 + shift + i + j)];
  return h;
}

}  // namespace

Index suggest_order(const Eigen::VectorXd& sv, double zero_tolerance) {
  const Index len = sv.size();
  if (len == 0) throw Error("suggest_order: no singular values");
  if (!(sv(0) > 0.0)) throw InsufficientData("suggest_order: all singular values are zero (no response in the data)");
  if (len == 1) return 1;
  // Ratios of consecutive singular values, each floored at zero_tolerance * largest so that a
  // numerically zero one ends the search with a large but finite gap.
  const double floor = zero_tolerance * sv(0);
  Index best = 1;
  double best_gap = -1.0;
  for (Index i = 0; i + 1 < len; ++i) {
    if (sv(i) <= floor) break;
    const double gap = std::log(sv(i) / std::max(sv(i + 1), floor));
    if (gap > best_gap) {
      best_gap = gap;
      best = i + 1;
    }
    if (sv(i + 1) <= floor) break;
  }
  return best;
}

EraResult era(const MarkovSequence& markov, double sample_time, const EraOptions& options) {
  if (markov.size() < 3)
    throw Error("ERA: needs Y_0 and at least two more Markov parameters, got " + std::to_string(markov.size()));
  const Index p = markov[0].rows(), m = markov[0].cols();
  if (p < 1 || m < 1) throw Error("ERA: Markov parameters must be at least 1x1");
  for (std::size_t k = 0; k < markov.size(); ++k) {
    if (markov[k].rows() != p || markov[k].cols() != m)
      throw Error("ERA: Markov parameter " + std::to_string(k) + " is " + std::to_string(markov[k].rows()) + "x" +
                  std::to_string(markov[k].cols()) + ", expected " + std::to_string(p) + "x" + std::to_string(m));
    if (!markov[k].allFinite()) throw Error("ERA: Markov parameter " + std::to_string(k) + " is not finite");
  }
  if (!(sample_time > 0.0) || !std::isfinite(sample_time))
    throw Error("ERA: sample time must be positive and finite, got " + num(sample_time));
  if (options.order < 0) throw Error("ERA: order must be >= 0, got " + std::to_string(options.order));
  const bool dc = options.data_correlation;
  const Index xi = dc ? options.correlation_blocks : 0;
  if (xi < 0) throw Error("ERA/DC: correlation_blocks must be >= 0, got " + std::to_string(xi));
  const Index J = static_cast<Index>(markov.size()) - 1;

  Index r = options.block_rows, s = options.block_columns;
  if (r == 0 && s == 0) {
    const Index budget = J - 2 * xi;
    r = static_cast<Index>(
        std::floor(static_cast<double>(budget) * static_cast<double>(m) / static_cast<double>(p + m)));
    r = std::max<Index>(r, 1);
    s = budget - r;
  } else if (r == 0 || s == 0) {
    throw Error("ERA: give both block_rows and block_columns, or neither");
  }
  if (r < 1 || s < 1 || r + s + 2 * xi > J)
    throw Error("ERA: " + std::to_string(r) + " block rows and " + std::to_string(s) + " block columns" +
                (dc ? " with " + std::to_string(xi) + " correlation blocks" : std::string()) +
                " need Markov parameters up to Y_" + std::to_string(r + s + 2 * xi) + ", got up to Y_" +
                std::to_string(J));

  EraResult out;
  out.block_rows = r;
  out.block_columns = s;
  const Eigen::MatrixXd H0 = hankel(markov, r, s, 0);

  Eigen::MatrixXd U, V, Hshift;
  Eigen::VectorXd sv;
  {
    linalg::Svd svd = linalg::svd(H0);
    out.hankel_singular_values = svd.S;
    if (!dc) {
      U = std::move(svd.U);
      V = std::move(svd.V);
      sv = std::move(svd.S);
      Hshift = hankel(markov, r, s, 1);
    }
  }
  if (dc) {
    std::vector<Eigen::MatrixXd> R;  // R(k) = H(k) H(0)', k = 0 .. 2 xi + 1
    for (Index k = 0; k <= 2 * xi + 1; ++k) R.push_back(hankel(markov, r, s, k) * H0.transpose());
    const Index b = p * r;
    Eigen::MatrixXd C0((xi + 1) * b, (xi + 1) * b), C1((xi + 1) * b, (xi + 1) * b);
    for (Index i = 0; i <= xi; ++i)
      for (Index j = 0; j <= xi; ++j) {
        C0.block(i * b, j * b, b, b) = R[static_cast<std::size_t>(i + j)];
        C1.block(i * b, j * b, b, b) = R[static_cast<std::size_t>(i + j + 1)];
      }
    linalg::Svd svd = linalg::svd(C0);
    U = std::move(svd.U);
    V = std::move(svd.V);
    sv = std::move(svd.S);
    out.correlation_singular_values = sv;
    Hshift = C1;
  }

  out.suggested_order = suggest_order(sv);
  const Index n = options.order > 0 ? options.order : out.suggested_order;
  const Index max_order = std::min(p * r, m * s);
  if (n > max_order)
    throw Error("ERA: order " + std::to_string(n) + " exceeds what a Hankel matrix of " + std::to_string(r) + "x" +
                std::to_string(s) + " blocks of " + std::to_string(p) + "x" + std::to_string(m) + " can realise (" +
                std::to_string(max_order) + "); give more Markov parameters");
  const double floor =
      std::max(1e-13, static_cast<double>(std::max(U.rows(), V.rows())) * std::numeric_limits<double>::epsilon()) *
      sv(0);
  if (!(sv(n - 1) > floor))
    throw InsufficientData("ERA: order " + std::to_string(n) +
                           " exceeds the numerical rank of the Hankel matrix (singular value " + std::to_string(n) +
                           " is " + num(sv(n - 1)) + ", largest " + num(sv(0)) + "); the data show at most " +
                           std::to_string(suggest_order(sv)) + " states");
  if (options.min_gap > 1.0 && n < sv.size() && !(sv(n - 1) >= options.min_gap * sv(n)))
    throw UndeterminedOrder("ERA: the data do not determine " + std::to_string(n) + " states: singular value " +
                            std::to_string(n) + " (" + num(sv(n - 1) / sv(0)) + " of the largest) is not " +
                            num(options.min_gap) + " times singular value " + std::to_string(n + 1) + " (" +
                            num(sv(n) / sv(0)) +
                            "), the floor the noise and the ARX truncation put under them; a longer record, more "
                            "excitation or less noise is needed");
  out.order = n;

  const Eigen::MatrixXd Un = U.leftCols(n), Vn = V.leftCols(n);
  const Eigen::VectorXd sq = sv.head(n).cwiseSqrt();
  const Eigen::VectorXd isq = sq.cwiseInverse();
  DiscreteSystem& sys = out.system;
  sys.sample_time = sample_time;
  sys.A = isq.asDiagonal() * (Un.transpose() * Hshift * Vn) * isq.asDiagonal();
  sys.D = markov[0];
  if (!dc) {
    sys.B = (sq.asDiagonal() * Vn.transpose()).leftCols(m);
    sys.C = (Un * sq.asDiagonal()).topRows(p);
  } else {
    const Eigen::MatrixXd P = (Un * sq.asDiagonal()).topRows(p * r);  // observability matrix, p r x n
    sys.C = P.topRows(p);
    sys.B = linalg::qr_solve(P, Eigen::MatrixXd(H0.leftCols(m))).x;
  }
  return out;
}

}  // namespace ambid::ident
