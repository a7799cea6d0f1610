#include "identifier/frequency_domain/frf_local_polynomial.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.hpp"
#include "core/linalg.hpp"

namespace ambid::ident {
namespace {

InsufficientData rank_deficient(Eigen::Index line, Eigen::Index rank, Eigen::Index unknowns) {
  return InsufficientData("local polynomial FRF: the local problem around line " + std::to_string(line) +
                          " is rank deficient (rank " + std::to_string(rank) + " of " + std::to_string(unknowns) + ")");
}

}  // namespace

std::vector<Eigen::MatrixXcd> local_polynomial_frf(const std::vector<Eigen::MatrixXcd>& X,
                                                   const std::vector<Eigen::MatrixXcd>& Z,
                                                   const std::vector<Eigen::Index>& lines,
                                                   const LocalPolynomialOptions& o) {
  const auto P = static_cast<Eigen::Index>(X.size());
  const auto nl = static_cast<Eigen::Index>(lines.size());
  if (P < 1 || Z.size() != X.size()) throw Error("local polynomial FRF: need one X and one Z per period position");
  if (o.degree < 0 || o.half_width < 0 || o.denominator_degree < 0)
    throw Error("local polynomial FRF: degrees and half width must be >= 0");
  const Eigen::Index nx = X.front().cols(), nz = Z.front().cols();
  for (Eigen::Index q = 0; q < P; ++q) {
    const auto qi = static_cast<std::size_t>(q);
    if (X[qi].rows() != nl || Z[qi].rows() != nl || X[qi].cols() != nx || Z[qi].cols() != nz)
      throw Error("local polynomial FRF: inconsistent sizes at period position " + std::to_string(q));
  }
  const Eigen::Index D1 = o.degree + 1;
  const Eigen::Index unknowns = (nx + (o.transient ? P : 0)) * D1;  // per response
  const Eigen::Index Dd = o.denominator_degree;
  Eigen::Index R = o.half_width;
  if (R == 0)
    R = std::max<Eigen::Index>(
        1, static_cast<Eigen::Index>(std::ceil(0.75 * static_cast<double>(unknowns + Dd) / static_cast<double>(P))));
  const Eigen::Index w = std::min<Eigen::Index>(2 * R + 1, nl);
  if (P * w < unknowns + Dd + 1)
    throw InsufficientData("local polynomial FRF: " + std::to_string(nl) + " lines are too few for a window of " +
                           std::to_string(2 * R + 1) + " lines (" + std::to_string(unknowns) + " unknowns per line)");

  // Real signals: X(-k) = conj X(k), and the FRF and the transient are Hermitian in the same
  // way, so the lines below the band mirror through DC to give the lowest lines a centred window.
  Eigen::Index mirrored = 0;
  while (mirrored < nl && mirrored < R && lines[static_cast<std::size_t>(mirrored)] > 0) ++mirrored;
  const Eigen::Index ne = nl + mirrored;
  std::vector<Eigen::Index> ext_lines(static_cast<std::size_t>(ne));
  std::vector<Eigen::MatrixXcd> Xe(static_cast<std::size_t>(P)), Ze(static_cast<std::size_t>(P));
  for (Eigen::Index q = 0; q < P; ++q) {
    const auto qi = static_cast<std::size_t>(q);
    Xe[qi].resize(ne, nx);
    Ze[qi].resize(ne, nz);
    for (Eigen::Index i = 0; i < mirrored; ++i) {
      Xe[qi].row(i) = X[qi].row(mirrored - 1 - i).conjugate();
      Ze[qi].row(i) = Z[qi].row(mirrored - 1 - i).conjugate();
    }
    Xe[qi].bottomRows(nl) = X[qi];
    Ze[qi].bottomRows(nl) = Z[qi];
  }
  for (Eigen::Index i = 0; i < mirrored; ++i)
    ext_lines[static_cast<std::size_t>(i)] = -lines[static_cast<std::size_t>(mirrored - 1 - i)];
  for (Eigen::Index i = 0; i < nl; ++i)
    ext_lines[static_cast<std::size_t>(mirrored + i)] = lines[static_cast<std::size_t>(i)];
  const Eigen::Index we = std::min<Eigen::Index>(2 * R + 1, ne);

  std::vector<Eigen::MatrixXcd> out;
  out.reserve(static_cast<std::size_t>(nl));
  Eigen::MatrixXcd Phi(P * we, unknowns), rhs(P * we, nz);
  for (Eigen::Index l = 0; l < nl; ++l) {
    const Eigen::Index c = mirrored + l;  // the centre in the extended list
    const Eigen::Index a = std::clamp<Eigen::Index>(c - R, 0, ne - we);
    const Eigen::Index kc = ext_lines[static_cast<std::size_t>(c)];
    double scale = 1.0;
    for (Eigen::Index i = a; i < a + we; ++i)
      scale = std::max(scale, std::abs(static_cast<double>(ext_lines[static_cast<std::size_t>(i)] - kc)));
    Phi.setZero();
    for (Eigen::Index q = 0; q < P; ++q) {
      const auto qi = static_cast<std::size_t>(q);
      for (Eigen::Index i = 0; i < we; ++i) {
        const Eigen::Index row = q * we + i;
        const double delta = static_cast<double>(ext_lines[static_cast<std::size_t>(a + i)] - kc) / scale;
        double p = 1.0;
        for (Eigen::Index d = 0; d < D1; ++d) {
          for (Eigen::Index s = 0; s < nx; ++s) Phi(row, s * D1 + d) = Xe[qi](a + i, s) * p;
          if (o.transient) Phi(row, nx * D1 + q * D1 + d) = p;
          p *= delta;
        }
        rhs.row(row) = Ze[qi].row(a + i);
      }
    }
    // Equilibrate the columns (references and the unit transient columns differ in scale).
    Eigen::VectorXd norms = Phi.colwise().norm().transpose();
    for (Eigen::Index col = 0; col < unknowns; ++col) {
      if (!(norms(col) > 0.0))
        throw InsufficientData("local polynomial FRF: a regressor vanishes around line " + std::to_string(kc));
      Phi.col(col) /= norms(col);
    }
    Eigen::MatrixXcd G(nz, nx);
    if (Dd == 0) {
      const linalg::RankedSolution<Eigen::MatrixXcd> ls = linalg::qr_solve(Phi, rhs, 1e-10);
      if (ls.rank < unknowns) throw rank_deficient(kc, ls.rank, unknowns);
      for (Eigen::Index s = 0; s < nx; ++s) G.col(s) = ls.x.row(s * D1).transpose() / norms(s * D1);
    } else {
      // Common denominator 1 + sum a_d delta^d of every response: Z = N X + T - (D - 1) Z, one
      // least-squares problem coupling the responses through a_d.
      const Eigen::Index rows = P * we, cols = nz * unknowns + Dd;
      Eigen::MatrixXcd A = Eigen::MatrixXcd::Zero(nz * rows, cols);
      Eigen::MatrixXcd b(nz * rows, 1);
      for (Eigen::Index j = 0; j < nz; ++j) {
        A.block(j * rows, j * unknowns, rows, unknowns) = Phi;
        b.middleRows(j * rows, rows) = rhs.col(j);
        for (Eigen::Index q = 0; q < P; ++q)
          for (Eigen::Index i = 0; i < we; ++i) {
            const double delta = static_cast<double>(ext_lines[static_cast<std::size_t>(a + i)] - kc) / scale;
            double p = delta;
            for (Eigen::Index d = 0; d < Dd; ++d, p *= delta)
              A(j * rows + q * we + i, nz * unknowns + d) = -p * rhs(q * we + i, j);
          }
      }
      Eigen::VectorXd den_norms = A.rightCols(Dd).colwise().norm().transpose();
      for (Eigen::Index d = 0; d < Dd; ++d) {
        if (!(den_norms(d) > 0.0)) den_norms(d) = 1.0;
        A.col(nz * unknowns + d) /= den_norms(d);
      }
      const linalg::RankedSolution<Eigen::MatrixXcd> ls = linalg::qr_solve(A, b, 1e-10);
      if (ls.rank < cols) throw rank_deficient(kc, ls.rank, cols);
      for (Eigen::Index j = 0; j < nz; ++j)
        for (Eigen::Index s = 0; s < nx; ++s) G(j, s) = ls.x(j * unknowns + s * D1, 0) / norms(s * D1);
    }
    out.push_back(G);
  }
  return out;
}

}  // namespace ambid::ident
