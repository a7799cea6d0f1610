#include "identifier/frequency_domain/frf_stepped_sine.hpp"

#include <algorithm>
#include <complex>
#include <numbers>
#include <sstream>
#include <string>

#include "core/error.hpp"

namespace ambid::ident {
namespace {

struct StepPhasors {
  double frequency_hz;
  std::complex<double> r, u;
  Eigen::VectorXcd y;
};

// (2/M) sum_n x(start + n, c) e^{-j 2 pi k n / M} for every column: the DFT line k of the
// window, computed directly (an FFT of a window of prime length would cost M^2).
Eigen::VectorXcd window_phasor(const Eigen::MatrixXd& x, Eigen::Index start, Eigen::Index M, Eigen::Index k) {
  Eigen::VectorXcd out = Eigen::VectorXcd::Zero(x.cols());
  for (Eigen::Index n = 0; n < M; ++n) {
    // k n mod M keeps the argument small, so the phase is exact to rounding for any record.
    const double angle = -2.0 * std::numbers::pi * static_cast<double>((k * n) % M) / static_cast<double>(M);
    out += std::polar(1.0, angle) * x.row(start + n).transpose().cast<std::complex<double>>();
  }
  return out * (2.0 / static_cast<double>(M));
}

std::string step_name(std::size_t i, double f) {
  std::ostringstream s;
  s << "stepped sine: step " << i << " (" << f << " Hz)";
  return s.str();
}

void check_inputs(const Eigen::MatrixXd& r, const Eigen::MatrixXd& u, const Eigen::MatrixXd& y,
                  const SteppedSineFrfOptions& o) {
  if (!(o.sample_time > 0.0))
    throw Error("stepped sine: sample_time must be positive, got " + std::to_string(o.sample_time));
  if (r.rows() != u.rows() || r.rows() != y.rows())
    throw Error("stepped sine: r, u and y must have the same number of samples (" + std::to_string(r.rows()) + ", " +
                std::to_string(u.rows()) + ", " + std::to_string(y.rows()) + ")");
  if (r.cols() != 1 || u.cols() != 1)
    throw InsufficientData(
        "stepped sine: one sine per step excites one direction; it needs exactly one reference and "
        "one plant input, got " +
        std::to_string(r.cols()) + " references and " + std::to_string(u.cols()) + " plant inputs");
  if (o.steps.empty()) throw InsufficientData("stepped sine: no steps");
}

}  // namespace

SteppedSineFrf estimate_stepped_sine_frf(const Eigen::MatrixXd& r, const Eigen::MatrixXd& u, const Eigen::MatrixXd& y,
                                         const SteppedSineFrfOptions& o) {
  check_inputs(r, u, y, o);
  std::vector<StepPhasors> phasors;
  for (std::size_t i = 0; i < o.steps.size(); ++i) {
    const SteppedSineStep& s = o.steps[i];
    const double f = static_cast<double>(s.cycles) / (static_cast<double>(s.measure_samples) * o.sample_time);
    if (s.measure_start < 0 || s.measure_samples < 2 || s.measure_start + s.measure_samples > r.rows())
      throw Error(step_name(i, f) + ": window [" + std::to_string(s.measure_start) + ", +" +
                  std::to_string(s.measure_samples) + ") is outside the record of " + std::to_string(r.rows()) +
                  " samples");
    if (s.cycles < 1 || 2 * s.cycles >= s.measure_samples)
      throw Error(step_name(i, f) + ": " + std::to_string(s.cycles) + " cycles in " +
                  std::to_string(s.measure_samples) + " samples is not below the Nyquist frequency");
    if (f < o.f_min || (o.f_max > 0.0 && f > o.f_max)) continue;
    const auto one = [&](const Eigen::MatrixXd& x) {
      return window_phasor(x, s.measure_start, s.measure_samples, s.cycles);
    };
    const Eigen::VectorXcd R = one(r), U = one(u), Y = one(y);
    // The reference must be there at all: a step whose r phasor is at rounding level of the
    // recorded r cannot be divided by.
    if (!(std::abs(R(0)) > 1e-9 * std::max(r.cwiseAbs().maxCoeff(), 1e-300)))
      throw InsufficientData(step_name(i, f) + ": the reference has no component at the step frequency");
    if (!(std::abs(U(0)) > 1e-12 * std::abs(R(0))))
      throw InsufficientData(step_name(i, f) + ": the plant input has no component at the step frequency (T_ur = 0)");
    phasors.push_back({f, R(0), U(0), Y});
  }
  if (phasors.empty()) throw InsufficientData("stepped sine: no step in the requested band");
  std::sort(phasors.begin(), phasors.end(),
            [](const StepPhasors& a, const StepPhasors& b) { return a.frequency_hz < b.frequency_hz; });
  for (std::size_t i = 1; i < phasors.size(); ++i)
    if (!(phasors[i].frequency_hz > phasors[i - 1].frequency_hz))
      throw Error("stepped sine: two steps at " + std::to_string(phasors[i].frequency_hz) + " Hz");

  SteppedSineFrf out;
  const auto n = static_cast<Eigen::Index>(phasors.size());
  for (Frf* frf : {&out.plant, &out.plant_direct, &out.output_from_reference, &out.input_from_reference})
    frf->frequency_hz.resize(n);
  for (Eigen::Index l = 0; l < n; ++l) {
    const StepPhasors& p = phasors[static_cast<std::size_t>(l)];
    for (Frf* frf : {&out.plant, &out.plant_direct, &out.output_from_reference, &out.input_from_reference})
      frf->frequency_hz(l) = p.frequency_hz;
    const Eigen::VectorXcd T_yr = p.y / p.r;
    const std::complex<double> T_ur = p.u / p.r;
    out.output_from_reference.value.push_back(T_yr);
    out.input_from_reference.value.push_back(Eigen::MatrixXcd::Constant(1, 1, T_ur));
    out.plant.value.push_back(T_yr / T_ur);
    out.plant_direct.value.push_back(p.y / p.u);
  }
  return out;
}

}  // namespace ambid::ident
