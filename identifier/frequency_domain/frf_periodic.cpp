#include "identifier/frequency_domain/frf_periodic.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.hpp"
#include "identifier/frequency_domain/frf_dft.hpp"
#include "identifier/frequency_domain/frf_linalg.hpp"
#include "identifier/frequency_domain/frf_period_scatter.hpp"

namespace ambid::ident {
namespace {

// Reference (or response) phasors of block b at line l, one column per period of the block.
Eigen::MatrixXcd block_matrix(const std::vector<Eigen::MatrixXcd>& phasors, Eigen::Index b, Eigen::Index P,
                              Eigen::Index l) {
  const Eigen::Index channels = phasors.front().cols();
  Eigen::MatrixXcd M(channels, P);
  for (Eigen::Index q = 0; q < P; ++q) M.col(q) = phasors[static_cast<std::size_t>(b * P + q)].row(l).transpose();
  return M;
}

// Element-wise |x|^2 summed over a list of deviations, divided by `divisor`.
Eigen::MatrixXd spread(const std::vector<Eigen::MatrixXcd>& deviations, double divisor) {
  Eigen::MatrixXd s = Eigen::MatrixXd::Zero(deviations.front().rows(), deviations.front().cols());
  for (const auto& d : deviations) s += d.cwiseAbs2();
  return s / divisor;
}

std::string line_text(Eigen::Index k, double f) {
  return "line " + std::to_string(k) + " (" + std::to_string(f) + " Hz)";
}

void check_options(const Eigen::MatrixXd& r, const Eigen::MatrixXd& u, const Eigen::MatrixXd& y,
                   const PeriodicFrfOptions& o) {
  if (u.rows() != r.rows() || y.rows() != r.rows())
    throw Error("periodic FRF: r, u, y must have the same number of samples, got " + std::to_string(r.rows()) + ", " +
                std::to_string(u.rows()) + ", " + std::to_string(y.rows()));
  if (r.cols() < 1 || u.cols() < 1 || y.cols() < 1)
    throw Error("periodic FRF: need at least one reference, input and output");
  if (!r.allFinite() || !u.allFinite() || !y.allFinite()) throw Error("periodic FRF: the data are not finite");
  if (!(o.sample_time > 0.0) || !std::isfinite(o.sample_time))
    throw Error("periodic FRF: sample_time must be positive, got " + std::to_string(o.sample_time));
  if (o.period_samples < 4)
    throw Error("periodic FRF: period_samples must be at least 4, got " + std::to_string(o.period_samples));
  if (o.lines.empty()) throw Error("periodic FRF: no excited lines given");
  for (std::size_t i = 0; i < o.lines.size(); ++i) {
    const Eigen::Index k = o.lines[i];
    if (k <= 0 || 2 * k >= o.period_samples)
      throw Error("periodic FRF: line " + std::to_string(k) +
                  " is outside (0, N/2) for N = " + std::to_string(o.period_samples));
    if (i > 0 && k <= o.lines[i - 1])
      throw Error("periodic FRF: lines must increase strictly, got " + std::to_string(k) + " after " +
                  std::to_string(o.lines[i - 1]));
  }
  if (o.first_sample < 0) throw Error("periodic FRF: first_sample must be >= 0, got " + std::to_string(o.first_sample));
  if (!o.left_out.empty() && std::ssize(o.left_out) != r.rows())
    throw Error("periodic FRF: the mask of left-out samples has " + std::to_string(o.left_out.size()) +
                " entries for " + std::to_string(r.rows()) + " samples");
  if (o.transient_periods < 0)
    throw Error("periodic FRF: transient_periods must be >= 0, got " + std::to_string(o.transient_periods));
  // Fewer periods per block than references: only the local polynomial method separates the
  // references, through their different spectra on neighbouring lines (e.g. zippered grids).
  if (o.periods_per_block < r.cols() && o.transient_model != PeriodicFrfOptions::TransientModel::local_polynomial)
    throw Error("periodic FRF: " + std::to_string(r.cols()) +
                " references need at least as many periods per block, got " + std::to_string(o.periods_per_block));
  if (r.cols() < u.cols())
    throw Error("periodic FRF: the plant estimate needs at least as many references as plant inputs, got " +
                std::to_string(r.cols()) + " references for " + std::to_string(u.cols()) + " inputs");
}

}  // namespace

PeriodicFrf estimate_periodic_frf(const Eigen::MatrixXd& r, const Eigen::MatrixXd& u, const Eigen::MatrixXd& y,
                                  const PeriodicFrfOptions& o) {
  check_options(r, u, y, o);
  const Eigen::Index N = o.period_samples, P = o.periods_per_block;
  const Eigen::Index available = (r.rows() - o.first_sample) / N;
  const Eigen::Index usable = available - o.transient_periods;
  Eigen::Index B = usable > 0 ? usable / P : 0;
  if (B < 1)
    throw InsufficientData("periodic FRF: " + std::to_string(available) + " whole periods of " + std::to_string(N) +
                           " samples, " + std::to_string(o.transient_periods) +
                           " discarded as transient, leave no block of " + std::to_string(P) + " periods");
  const Eigen::Index start = o.first_sample + o.transient_periods * N;
  // The blocks kept: none that holds a left-out sample or follows one that does.
  std::vector<Eigen::Index> kept;
  bool after_left_out = false;
  for (Eigen::Index b = 0; b < B; ++b) {
    const auto first = start + b * P * N;
    const bool holds = !o.left_out.empty() && std::find(o.left_out.begin() + first, o.left_out.begin() + first + P * N,
                                                        true) != o.left_out.begin() + first + P * N;
    if (!holds && !after_left_out) kept.push_back(b);
    after_left_out = holds;
  }
  if (kept.empty())
    throw InsufficientData("periodic FRF: every one of the " + std::to_string(B) + " blocks of " + std::to_string(P) +
                           " periods holds a sample where a controller clamp acted, or follows one");
  auto phasors = [&](const Eigen::MatrixXd& x) {
    const auto all = period_phasors(x, start, N, B * P, o.lines);
    std::vector<Eigen::MatrixXcd> out;
    for (const Eigen::Index b : kept)
      for (Eigen::Index q = 0; q < P; ++q) out.push_back(all[static_cast<std::size_t>(b * P + q)]);
    return out;
  };
  const auto Rp = phasors(r), Up = phasors(u), Yp = phasors(y);
  const Eigen::Index blocks_left_out = B - static_cast<Eigen::Index>(kept.size());
  B = static_cast<Eigen::Index>(kept.size());

  const Eigen::Index nl = static_cast<Eigen::Index>(o.lines.size());
  const Eigen::Index ny = y.cols(), nu = u.cols(), nr = r.cols();
  PeriodicFrf out;
  out.blocks = B;
  out.periods_used = B * P;
  out.blocks_left_out = blocks_left_out;
  Eigen::VectorXd f(nl);
  for (Eigen::Index l = 0; l < nl; ++l)
    f(l) = static_cast<double>(o.lines[static_cast<std::size_t>(l)]) / (static_cast<double>(N) * o.sample_time);
  for (Frf* frf : {&out.plant, &out.plant_direct, &out.output_from_reference, &out.input_from_reference}) {
    frf->frequency_hz = f;
    frf->value.reserve(static_cast<std::size_t>(nl));
  }
  const bool with_variance = B >= 2;
  if (with_variance) {
    out.output_noise_variance.resize(nl, ny);
    out.input_noise_variance.resize(nl, nu);
    const double dof = 2.0 * static_cast<double>(B - 1);
    out.plant.variance_dof = out.output_from_reference.variance_dof = out.input_from_reference.variance_dof = dof;
  }

  // Excitation level of each line, to recognise lines that carry no excitation: against the
  // strongest line and the rms of the references over one period.
  Eigen::VectorXd level(nl);
  for (Eigen::Index l = 0; l < nl; ++l) level(l) = max_singular_value(block_matrix(Rp, 0, P, l));
  const double rms = std::sqrt(r.middleRows(start, N).squaredNorm() / static_cast<double>(N));
  const double top = std::max(level.maxCoeff(), rms);
  for (Eigen::Index l = 0; l < nl; ++l) {
    const Eigen::Index k = o.lines[static_cast<std::size_t>(l)];
    if (!(level(l) > 1e-9 * top))
      throw InsufficientData("periodic FRF: " + line_text(k, f(l)) + " carries no excitation (" +
                             std::to_string(level(l)) + " against " + std::to_string(top) + ")");
    for (Eigen::Index b = 0; P >= nr && b < B; ++b) {
      const Eigen::MatrixXcd R = block_matrix(Rp, b, P, l);
      if (const double ic = inverse_condition(R); !(ic > 1e-8))
        throw InsufficientData("periodic FRF: at " + line_text(k, f(l)) + " the " + std::to_string(nr) +
                               " references of block " + std::to_string(b) + " are not independent over its " +
                               std::to_string(P) + " periods (inverse condition " + std::to_string(ic) +
                               "); use an orthogonal (e.g. Hadamard) channel pattern");
    }
  }

  // Per-block responses Tyr[b][l], Tur[b][l] and direct estimates Gd[b][l].
  using Lines = std::vector<Eigen::MatrixXcd>;
  std::vector<Lines> Tyr(static_cast<std::size_t>(B)), Tur(static_cast<std::size_t>(B)),
      Gd(static_cast<std::size_t>(B));
  const bool lpm = o.transient_model == PeriodicFrfOptions::TransientModel::local_polynomial ||
                   (o.transient_model == PeriodicFrfOptions::TransientModel::automatic && P > 1);
  for (Eigen::Index b = 0; b < B; ++b) {
    const auto bi = static_cast<std::size_t>(b);
    if (lpm) {
      std::vector<Eigen::MatrixXcd> X(static_cast<std::size_t>(P)), Z(static_cast<std::size_t>(P)),
          U(static_cast<std::size_t>(P)), Y(static_cast<std::size_t>(P));
      for (Eigen::Index q = 0; q < P; ++q) {
        const auto pi = static_cast<std::size_t>(b * P + q), qi = static_cast<std::size_t>(q);
        X[qi] = Rp[pi];
        Z[qi].resize(nl, ny + nu);
        Z[qi] << Yp[pi], Up[pi];
        U[qi] = Up[pi];
        Y[qi] = Yp[pi];
      }
      const Lines T = local_polynomial_frf(X, Z, o.lines, o.local_polynomial);
      for (const auto& t : T) {
        Tyr[bi].push_back(t.topRows(ny));
        Tur[bi].push_back(t.bottomRows(nu));
      }
      Gd[bi] = local_polynomial_frf(U, Y, o.lines, o.local_polynomial);
    } else {
      for (Eigen::Index l = 0; l < nl; ++l) {
        const Eigen::MatrixXcd R = block_matrix(Rp, b, P, l);
        Tyr[bi].push_back(right_solve(block_matrix(Yp, b, P, l), R));
        Tur[bi].push_back(right_solve(block_matrix(Up, b, P, l), R));
        Gd[bi].push_back(right_solve(block_matrix(Yp, b, P, l), block_matrix(Up, b, P, l)));
      }
    }
  }

  const double b_count = static_cast<double>(B);
  const bool from_means = o.plant_from_period_means && lpm && P == 1;
  for (Eigen::Index l = 0; l < nl; ++l) {
    const auto li = static_cast<std::size_t>(l);
    const Eigen::Index k = o.lines[li];
    Eigen::MatrixXcd Tyr_mean = Eigen::MatrixXcd::Zero(ny, nr), Tur_mean = Eigen::MatrixXcd::Zero(nu, nr);
    for (Eigen::Index b = 0; b < B; ++b) {
      Tyr_mean += Tyr[static_cast<std::size_t>(b)][li];
      Tur_mean += Tur[static_cast<std::size_t>(b)][li];
    }
    Tyr_mean /= b_count;
    Tur_mean /= b_count;
    if (const double ic = inverse_condition(Tur_mean); !(ic > 1e-10))
      throw InsufficientData("periodic FRF: at " + line_text(k, f(l)) +
                             " the response of the plant inputs to the references is singular (inverse condition " +
                             std::to_string(ic) + ")");
    const Eigen::MatrixXcd G = right_solve(Tyr_mean, Tur_mean);
    out.output_from_reference.value.push_back(Tyr_mean);
    out.input_from_reference.value.push_back(Tur_mean);
    out.plant.value.push_back(G);

    // Direct estimate: over every period used (least squares), or the block average of the
    // local polynomial estimates.
    if (lpm) {
      Eigen::MatrixXcd Gd_mean = Eigen::MatrixXcd::Zero(ny, nu);
      for (Eigen::Index b = 0; b < B; ++b) Gd_mean += Gd[static_cast<std::size_t>(b)][li];
      out.plant_direct.value.push_back(Gd_mean / b_count);
    } else {
      Eigen::MatrixXcd Yall(ny, B * P), Uall(nu, B * P);
      for (Eigen::Index b = 0; b < B; ++b) {
        Yall.middleCols(b * P, P) = block_matrix(Yp, b, P, l);
        Uall.middleCols(b * P, P) = block_matrix(Up, b, P, l);
      }
      out.plant_direct.value.push_back(right_solve(Yall, Uall));
    }

    if (with_variance) {
      const double divisor = b_count * (b_count - 1.0);  // variance of the mean
      std::vector<Eigen::MatrixXcd> dy, du, dg;
      // Right inverse of T_ur (inputs x references, full row rank): T_ur T_ur^+ = I.
      const Eigen::MatrixXcd Tur_pinv = left_solve(Tur_mean, Eigen::MatrixXcd::Identity(nu, nu));
      Eigen::MatrixXcd dg_mean = Eigen::MatrixXcd::Zero(ny, nu);
      for (Eigen::Index b = 0; b < B; ++b) {
        const auto bi = static_cast<std::size_t>(b);
        dy.push_back(Tyr[bi][li] - Tyr_mean);
        du.push_back(Tur[bi][li] - Tur_mean);
        dg.push_back((Tyr[bi][li] - G * Tur[bi][li]) * Tur_pinv);
        dg_mean += dg.back();
      }
      dg_mean /= b_count;
      for (auto& d : dg) d -= dg_mean;
      out.output_from_reference.variance.push_back(spread(dy, divisor));
      out.input_from_reference.variance.push_back(spread(du, divisor));
      out.plant.variance.push_back(spread(dg, divisor));

      // Noise of one period's phasor: spread across blocks at each position of the block.
      Eigen::VectorXd vy = Eigen::VectorXd::Zero(ny), vu = Eigen::VectorXd::Zero(nu);
      for (Eigen::Index q = 0; q < P; ++q) {
        Eigen::VectorXcd my = Eigen::VectorXcd::Zero(ny), mu = Eigen::VectorXcd::Zero(nu);
        for (Eigen::Index b = 0; b < B; ++b) {
          my += Yp[static_cast<std::size_t>(b * P + q)].row(l).transpose();
          mu += Up[static_cast<std::size_t>(b * P + q)].row(l).transpose();
        }
        my /= b_count;
        mu /= b_count;
        for (Eigen::Index b = 0; b < B; ++b) {
          vy += (Yp[static_cast<std::size_t>(b * P + q)].row(l).transpose() - my).cwiseAbs2();
          vu += (Up[static_cast<std::size_t>(b * P + q)].row(l).transpose() - mu).cwiseAbs2();
        }
      }
      const double positions = static_cast<double>(P) * (b_count - 1.0);
      out.output_noise_variance.row(l) = (vy / positions).transpose();
      out.input_noise_variance.row(l) = (vu / positions).transpose();
    }
  }
  if (from_means) {
    Eigen::MatrixXcd U_mean = Eigen::MatrixXcd::Zero(nl, nu), Y_mean = Eigen::MatrixXcd::Zero(nl, ny);
    for (Eigen::Index b = 0; b < B; ++b) {
      U_mean += Up[static_cast<std::size_t>(b)];
      Y_mean += Yp[static_cast<std::size_t>(b)];
    }
    U_mean /= b_count;
    Y_mean /= b_count;
    out.plant.value = local_polynomial_frf({U_mean}, {Y_mean}, o.lines, o.local_polynomial);
    if (with_variance) {
      // The same local model of each period alone, on the mean inputs, with that period's
      // noise moved to the outputs to first order: Y_b - G (U_b - U_mean), whose mean over the
      // periods is Y_mean. The scatter of these fits over the periods, with the loop's
      // transient separated (frf_period_scatter.hpp; not across left-out periods, where the
      // periods are not consecutive), is the variance of the estimate.
      std::vector<std::vector<Eigen::MatrixXcd>> Gb;
      for (Eigen::Index b = 0; b < B; ++b) {
        const auto bi = static_cast<std::size_t>(b);
        Eigen::MatrixXcd Yb = Yp[bi];
        for (Eigen::Index l = 0; l < nl; ++l)
          Yb.row(l) -=
              (out.plant.value[static_cast<std::size_t>(l)] * (Up[bi].row(l) - U_mean.row(l)).transpose()).transpose();
        Gb.push_back(local_polynomial_frf({U_mean}, {Yb}, o.lines, o.local_polynomial));
      }
      if (blocks_left_out == 0 && B >= 3) {
        out.plant.variance = period_mean_variance(Gb, std::max<Eigen::Index>(o.local_polynomial.half_width, 1));
      } else {
        for (Eigen::Index l = 0; l < nl; ++l) {
          const auto li = static_cast<std::size_t>(l);
          Eigen::MatrixXcd mean = Eigen::MatrixXcd::Zero(ny, nu);
          for (const auto& g : Gb) mean += g[li];
          mean /= b_count;
          std::vector<Eigen::MatrixXcd> deviations;
          for (const auto& g : Gb) deviations.push_back(g[li] - mean);
          out.plant.variance[li] = spread(deviations, b_count * (b_count - 1.0));
        }
      }
    }
  }
  return out;
}

}  // namespace ambid::ident
