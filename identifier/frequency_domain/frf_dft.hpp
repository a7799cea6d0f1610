#pragma once
// Exact DFT of whole periods at chosen lines (the leakage-free spectrum of periodic signals).
#include <vector>

#include <Eigen/Core>

namespace ambid::ident {

// Phasors of the DFT `lines` (indices within one period of `period` samples, 0 <= k <= N/2) of
// every column of x over `count` consecutive whole periods starting at sample `first`:
// result[p](l, c) = (2/N) sum_{n<N} x(first + p N + n, c) e^{-j 2 pi lines[l] n / N}.
// Throws Error when the periods do not fit in x, period < 2, count < 1 or a line is outside
// [0, N/2].
std::vector<Eigen::MatrixXcd> period_phasors(const Eigen::MatrixXd& x, Eigen::Index first, Eigen::Index period,
                                             Eigen::Index count, const std::vector<Eigen::Index>& lines);

}  // namespace ambid::ident
