#include "identifier/frf_welch.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include <unsupported/Eigen/FFT>

#include "core/error.hpp"
#include "identifier/frequency_domain/frf_linalg.hpp"

namespace ambid::ident {
namespace {

void check_options(const Eigen::MatrixXd& r, const Eigen::MatrixXd& u, const Eigen::MatrixXd& y,
                   const WelchFrfOptions& o) {
  if (u.rows() != r.rows() || y.rows() != r.rows())
    throw Error("Welch FRF: r, u, y must have the same number of samples, got " + std::to_string(r.rows()) + ", " +
                std::to_string(u.rows()) + ", " + std::to_string(y.rows()));
  if (r.cols() < 1 || u.cols() < 1 || y.cols() < 1)
    throw Error("Welch FRF: need at least one reference, input and output");
  if (r.cols() < u.cols())
    throw Error("Welch FRF: the plant estimate needs at least as many references as plant inputs, got " +
                std::to_string(r.cols()) + " references for " + std::to_string(u.cols()) + " inputs");
  if (!r.allFinite() || !u.allFinite() || !y.allFinite()) throw Error("Welch FRF: the data are not finite");
  if (!(o.sample_time > 0.0) || !std::isfinite(o.sample_time))
    throw Error("Welch FRF: sample_time must be positive, got " + std::to_string(o.sample_time));
  if (o.segment_samples < 8)
    throw Error("Welch FRF: segment_samples must be at least 8, got " + std::to_string(o.segment_samples));
  if (!(o.overlap >= 0.0 && o.overlap < 1.0))
    throw Error("Welch FRF: overlap must be in [0, 1), got " + std::to_string(o.overlap));
  if (o.first_sample < 0) throw Error("Welch FRF: first_sample must be >= 0, got " + std::to_string(o.first_sample));
  if (!(o.f_min >= 0.0) || !(o.f_max >= 0.0)) throw Error("Welch FRF: f_min and f_max must be >= 0");
  if (!o.left_out.empty() && std::ssize(o.left_out) != r.rows())
    throw Error("Welch FRF: the mask of left-out samples has " + std::to_string(o.left_out.size()) + " entries for " +
                std::to_string(r.rows()) + " samples");
}

}  // namespace

WelchFrf estimate_welch_frf(const Eigen::MatrixXd& r, const Eigen::MatrixXd& u, const Eigen::MatrixXd& y,
                            const WelchFrfOptions& o) {
  check_options(r, u, y, o);
  const Eigen::Index L = o.segment_samples;
  const Eigen::Index hop =
      std::max<Eigen::Index>(1, static_cast<Eigen::Index>(std::llround(static_cast<double>(L) * (1.0 - o.overlap))));
  const Eigen::Index available = r.rows() - o.first_sample;
  const Eigen::Index candidates = available >= L ? 1 + (available - L) / hop : 0;
  const Eigen::Index nr = r.cols(), nu = u.cols(), ny = y.cols(), nz = nr + nu + ny;
  // Segment starts, without those whose samples hold one left out.
  std::vector<Eigen::Index> starts;
  for (Eigen::Index m = 0; m < candidates; ++m) {
    const Eigen::Index start = o.first_sample + m * hop;
    if (o.left_out.empty() ||
        std::find(o.left_out.begin() + start, o.left_out.begin() + start + L, true) == o.left_out.begin() + start + L)
      starts.push_back(start);
  }
  const auto M = static_cast<Eigen::Index>(starts.size());
  if (M < nr + 1)
    throw InsufficientData("Welch FRF: " + std::to_string(available) + " samples give " + std::to_string(candidates) +
                           " segments of " + std::to_string(L) +
                           (candidates > M ? " (" + std::to_string(candidates - M) +
                                                 " of them hold a sample left out, a controller clamp acting)"
                                           : std::string()) +
                           "; need at least " + std::to_string(nr + 1));

  // Lines kept.
  const double df = 1.0 / (static_cast<double>(L) * o.sample_time);
  const double f_max = o.f_max > 0.0 ? o.f_max : std::numeric_limits<double>::infinity();
  std::vector<Eigen::Index> bins;
  for (Eigen::Index k = 1; 2 * k < L; ++k) {
    const double f = static_cast<double>(k) * df;
    if (f >= o.f_min && f <= f_max) bins.push_back(k);
  }
  if (bins.empty()) throw Error("Welch FRF: no line between f_min and f_max");
  const auto nb = static_cast<Eigen::Index>(bins.size());

  // Periodic Hann window and the correlation of overlapping segments.
  Eigen::VectorXd w(L);
  for (Eigen::Index n = 0; n < L; ++n)
    w(n) = 0.5 - 0.5 * std::cos(2.0 * std::numbers::pi * static_cast<double>(n) / static_cast<double>(L));
  const double w2 = w.squaredNorm();
  // Variance of the average relative to independent segments: 1 + (2 / M) sum over pairs of
  // kept segments that overlap of rho(shift)^2.
  double ratio = 1.0;
  for (std::size_t a = 0; a < starts.size(); ++a)
    for (std::size_t b = a + 1; b < starts.size() && starts[b] - starts[a] < L; ++b) {
      const Eigen::Index s = starts[b] - starts[a];
      const double rho = w.head(L - s).dot(w.tail(L - s)) / w2;
      ratio += 2.0 / static_cast<double>(M) * rho * rho;
    }

  Eigen::MatrixXd Z(r.rows(), nz);
  Z << r, u, y;
  std::vector<Eigen::MatrixXcd> S(bins.size(), Eigen::MatrixXcd::Zero(nz, nz));
  Eigen::FFT<double> fft;
  std::vector<double> segment(static_cast<std::size_t>(L));
  std::vector<std::complex<double>> spectrum;
  Eigen::MatrixXcd F(nb, nz);
  for (const Eigen::Index start : starts) {
    for (Eigen::Index c = 0; c < nz; ++c) {
      for (Eigen::Index n = 0; n < L; ++n) segment[static_cast<std::size_t>(n)] = w(n) * Z(start + n, c);
      fft.fwd(spectrum, segment);
      for (Eigen::Index b = 0; b < nb; ++b)
        F(b, c) = spectrum[static_cast<std::size_t>(bins[static_cast<std::size_t>(b)])];
    }
    for (Eigen::Index b = 0; b < nb; ++b)
      S[static_cast<std::size_t>(b)] += F.row(b).transpose() * F.row(b).conjugate();  // Z Z^H
  }

  WelchFrf out;
  out.segments = M;
  out.skipped_segments = candidates - M;
  out.effective_segments = static_cast<double>(M) / ratio;
  Eigen::VectorXd f(nb);
  for (Eigen::Index b = 0; b < nb; ++b) f(b) = static_cast<double>(bins[static_cast<std::size_t>(b)]) * df;
  for (Frf* frf : {&out.plant, &out.plant_direct, &out.output_from_reference, &out.input_from_reference}) {
    frf->frequency_hz = f;
    frf->value.reserve(bins.size());
  }
  out.output_coherence.resize(nb, ny);
  out.input_coherence.resize(nb, nu);
  const double dof_correction = static_cast<double>(M) / static_cast<double>(M - nr);

  for (Eigen::Index b = 0; b < nb; ++b) {
    const Eigen::MatrixXcd& Sb = S[static_cast<std::size_t>(b)];
    const Eigen::MatrixXcd Srr = Sb.block(0, 0, nr, nr);
    const Eigen::MatrixXcd Sur = Sb.block(nr, 0, nu, nr);
    const Eigen::MatrixXcd Syr = Sb.block(nr + nu, 0, ny, nr);
    const Eigen::MatrixXcd Suu = Sb.block(nr, nr, nu, nu);
    const Eigen::MatrixXcd Syu = Sb.block(nr + nu, nr, ny, nu);
    const Eigen::MatrixXcd Syy = Sb.block(nr + nu, nr + nu, ny, ny);
    const std::string where =
        "line " + std::to_string(bins[static_cast<std::size_t>(b)]) + " (" + std::to_string(f(b)) + " Hz)";
    if (const double ic = inverse_condition(Srr); !(ic > 1e-10))
      throw InsufficientData("Welch FRF: at " + where + " the references are not independent (inverse condition " +
                             std::to_string(ic) + ")");
    if (const double ic = inverse_condition(Sur); !(ic > 1e-10))
      throw InsufficientData("Welch FRF: at " + where +
                             " the plant inputs are not excited independently by the references "
                             "(inverse condition " +
                             std::to_string(ic) + ")");
    const Eigen::MatrixXcd Tyr = right_solve(Syr, Srr);
    const Eigen::MatrixXcd Tur = right_solve(Sur, Srr);
    const Eigen::MatrixXcd G = right_solve(Syr, Sur);
    out.output_from_reference.value.push_back(Tyr);
    out.input_from_reference.value.push_back(Tur);
    out.plant.value.push_back(G);
    out.plant_direct.value.push_back(right_solve(Syu, Suu));

    for (Eigen::Index i = 0; i < ny; ++i)
      out.output_coherence(b, i) =
          std::clamp((Tyr.row(i) * Syr.row(i).adjoint())(0, 0).real() / Syy(i, i).real(), 0.0, 1.0);
    for (Eigen::Index i = 0; i < nu; ++i)
      out.input_coherence(b, i) =
          std::clamp((Tur.row(i) * Sur.row(i).adjoint())(0, 0).real() / Suu(i, i).real(), 0.0, 1.0);

    // v = y - G u: its spectrum, and the reference-side factor of the variance.
    const Eigen::MatrixXcd Suy = Syu.adjoint();
    const Eigen::MatrixXcd Svv = Syy - G * Suy - Syu * G.adjoint() + G * Suu * G.adjoint();
    const Eigen::MatrixXcd Rinv = left_solve(Sur, Eigen::MatrixXcd::Identity(nu, nu));  // nr x nu, Sur Rinv = I
    const Eigen::MatrixXcd W = Rinv.adjoint() * Srr * Rinv;                             // nu x nu
    Eigen::MatrixXd var(ny, nu);
    for (Eigen::Index i = 0; i < ny; ++i)
      for (Eigen::Index j = 0; j < nu; ++j)
        var(i, j) = std::max(0.0, Svv(i, i).real()) * W(j, j).real() * dof_correction / out.effective_segments;
    out.plant.variance.push_back(var);
  }
  return out;
}

}  // namespace ambid::ident
