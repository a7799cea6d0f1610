#pragma once
// Variance of the mean of a per-period estimate over B consecutive periods, from the
// period-to-period scatter, with the loop's transient separated from the noise.
//
// In closed loop the noise fed back through the controller keeps the plant's state from
// repeating: one period's DFT holds, besides the noise n_b, the plant's free response
// t_b - t_{b+1} (t_b from the state where period b starts, a smooth function of frequency that
// is large near the plant's slow and unstable poles). In the mean over the periods it
// telescopes to (t_0 - t_B) / B, but it inflates the scatter of the periods: on amb1dof_voltage
// with sensor noise the plain scatter over-stated the variance of the mean 5-fold below
// 50 Hz. With the Fourier components over the periods D_j = (1/B) sum_b x_b e^{-2 pi i j b / B},
// j = 1 .. B-1, of one element x_b of the per-period estimates, and t_b independent from
// period to period,
//   E|D_j|^2 = alpha + beta g_j,  g_j = (2 + (B - 1) |1 - e^{2 pi i j / B}|^2) / B,
//   variance of the mean = alpha + 2 beta / B,
// alpha the noise's share, beta = E|t_b|^2 / B. The ratio rho = beta / alpha of each element
// is a least-squares fit of the normalised |D_j|^2 on g_j pooled over the neighbouring lines
// (clamped at 0: the plain scatter), then alpha = mean_j |D_j|^2 / (1 + rho g_j), which for a
// known rho is a sample variance on 2 (B - 1) real degrees of freedom like the plain scatter
// (to which it reduces for rho = 0).
#include <vector>

#include <Eigen/Core>

namespace ambid::ident {

// per_period[b][l]: the estimate of period b (consecutive periods, no gap) at line l, every
// matrix of one shape; B >= 3. pooled_half_width: lines on each side pooled for rho.
// Returns the variance of the mean of each element at each line. Throws Error for fewer than
// 3 periods or inconsistent shapes.
std::vector<Eigen::MatrixXd> period_mean_variance(const std::vector<std::vector<Eigen::MatrixXcd>>& per_period,
                                                  Eigen::Index pooled_half_width);

}  // namespace ambid::ident
