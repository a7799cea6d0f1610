#include "plant_sim/excitation.hpp"

#include <array>
#include <bit>
#include <cmath>
#include <complex>
#include <numbers>
#include <random>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>
#include <unsupported/Eigen/FFT>

#include "core/error.hpp"

namespace ambid::sim {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

[[noreturn]] void fail(const char* where, const std::string& what, double value) {
  std::ostringstream msg;
  msg << where << ": " << what << ", got " << value;
  throw Error(msg.str());
}

void require_common(const char* where, double sample_time, int channels) {
  if (!(sample_time > 0.0) || !std::isfinite(sample_time))
    fail(where, "sample_time must be positive and finite", sample_time);
  if (channels < 1) fail(where, "channels must be at least 1", channels);
}

void require_amplitude(const char* where, double amplitude) {
  if (!(amplitude >= 0.0) || !std::isfinite(amplitude))
    fail(where, "amplitude must be finite and non-negative", amplitude);
}

// Uniform in [0, 1) with 53 random bits, independent of the standard library's distributions.
double uniform01(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

// Box-Muller, one normal per call.
double standard_normal(std::mt19937_64& rng) {
  const double u1 = 1.0 - uniform01(rng);  // (0, 1]
  const double u2 = uniform01(rng);
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(kTwoPi * u2);
}

nlohmann::json common(const char* kind, Eigen::Index samples, int channels, double T) {
  return {{"kind", kind}, {"samples", samples}, {"channels", channels}, {"sample_time", T}};
}

// Fibonacci LFSR taps (1-based positions) of primitive polynomials, register lengths 2..32.
const std::array<std::vector<int>, 33>& lfsr_taps() {
  static const std::array<std::vector<int>, 33> taps = {{
      {},
      {},
      {2, 1},
      {3, 2},
      {4, 3},
      {5, 3},
      {6, 5},
      {7, 6},
      {8, 6, 5, 4},
      {9, 5},
      {10, 7},
      {11, 9},
      {12, 6, 4, 1},
      {13, 4, 3, 1},
      {14, 5, 3, 1},
      {15, 14},
      {16, 15, 13, 4},
      {17, 14},
      {18, 11},
      {19, 6, 2, 1},
      {20, 17},
      {21, 19},
      {22, 21},
      {23, 18},
      {24, 23, 22, 17},
      {25, 22},
      {26, 6, 2, 1},
      {27, 5, 2, 1},
      {28, 25},
      {29, 27},
      {30, 6, 4, 1},
      {31, 28},
      {32, 22, 2, 1},
  }};
  return taps;
}

// The register: bit t-1 holds position t; a clock shifts left and enters the feedback at bit 0.
// Output is bit n-1.
struct Lfsr {
  int n;
  std::uint64_t mask, feedback;

  explicit Lfsr(int length) : n(length), mask((std::uint64_t{1} << length) - 1), feedback(0) {
    for (const int t : lfsr_taps()[static_cast<std::size_t>(length)]) feedback |= std::uint64_t{1} << (t - 1);
  }
  std::uint64_t next(std::uint64_t s) const {
    const std::uint64_t bit = static_cast<std::uint64_t>(std::popcount(s & feedback) & 1);
    return ((s << 1) | bit) & mask;
  }
  bool output(std::uint64_t s) const { return ((s >> (n - 1)) & 1U) != 0; }

  // The state `clocks` steps after `s`, by powers of the (linear over GF(2)) step map.
  std::uint64_t advance(std::uint64_t s, std::uint64_t clocks) const {
    std::vector<std::uint64_t> step(static_cast<std::size_t>(n));  // columns: step(e_i)
    for (int i = 0; i < n; ++i) step[static_cast<std::size_t>(i)] = next(std::uint64_t{1} << i);
    auto apply = [&](const std::vector<std::uint64_t>& M, std::uint64_t v) {
      std::uint64_t out = 0;
      for (int i = 0; i < n; ++i)
        if ((v >> i) & 1U) out ^= M[static_cast<std::size_t>(i)];
      return out;
    };
    while (clocks != 0) {
      if (clocks & 1U) s = apply(step, s);
      std::vector<std::uint64_t> squared(step.size());
      for (std::size_t i = 0; i < step.size(); ++i) squared[i] = apply(step, step[i]);
      step = std::move(squared);
      clocks >>= 1;
    }
    return s;
  }
};

}  // namespace

Excitation prbs(const PrbsOptions& o, Eigen::Index samples, double sample_time) {
  const char* where = "PRBS";
  require_common(where, sample_time, o.channels);
  require_amplitude(where, o.amplitude);
  if (o.register_length < 2 || o.register_length > 32)
    fail(where, "register_length must be in 2..32", o.register_length);
  if (o.clock_divider < 1) fail(where, "clock_divider must be at least 1", o.clock_divider);
  if (samples < 0) fail(where, "samples must be non-negative", static_cast<double>(samples));

  const Lfsr lfsr(o.register_length);
  const std::uint64_t period = lfsr.mask;  // 2^n - 1
  std::mt19937_64 rng(o.seed);
  const std::uint64_t base = rng() % period;
  Excitation out;
  out.samples.resize(samples, o.channels);
  nlohmann::json shifts = nlohmann::json::array();
  for (int j = 0; j < o.channels; ++j) {
    const std::uint64_t shift =
        (base + static_cast<std::uint64_t>(j) * (period / static_cast<std::uint64_t>(o.channels))) % period;
    shifts.push_back(shift);
    std::uint64_t state = lfsr.advance(1, shift);
    for (Eigen::Index k = 0; k < samples; ++k) {
      if (k > 0 && k % o.clock_divider == 0) state = lfsr.next(state);
      out.samples(k, j) = lfsr.output(state) ? o.amplitude : -o.amplitude;
    }
  }
  const auto period_samples = static_cast<Eigen::Index>(period) * o.clock_divider;
  out.description.json() = common("prbs", samples, o.channels, sample_time);
  out.description.json().update({{"amplitude", o.amplitude},
                                 {"register_length", o.register_length},
                                 {"clock_divider", o.clock_divider},
                                 {"period_samples", period_samples},
                                 {"periods", static_cast<double>(samples) / static_cast<double>(period_samples)},
                                 {"channel_pattern", "shifted"},
                                 {"channel_shifts", shifts},
                                 {"seed", o.seed}});
  return out;
}

Excitation random_signal(const RandomOptions& o, Eigen::Index samples, double sample_time) {
  const char* where = "random excitation";
  require_common(where, sample_time, o.channels);
  require_amplitude(where, o.amplitude);
  if (o.clock_divider < 1) fail(where, "clock_divider must be at least 1", o.clock_divider);
  if (samples < 0) fail(where, "samples must be non-negative", static_cast<double>(samples));
  std::mt19937_64 master(o.seed);
  Excitation out;
  out.samples.resize(samples, o.channels);
  nlohmann::json seeds = nlohmann::json::array();
  for (int j = 0; j < o.channels; ++j) {
    const std::uint64_t channel_seed = master();
    seeds.push_back(channel_seed);
    std::mt19937_64 rng(channel_seed);
    double value = 0.0;
    for (Eigen::Index k = 0; k < samples; ++k) {
      if (k % o.clock_divider == 0)
        value = o.kind == NoiseKind::binary ? ((rng() >> 63) != 0 ? o.amplitude : -o.amplitude)
                                            : o.amplitude * standard_normal(rng);
      out.samples(k, j) = value;
    }
  }
  out.description.json() =
      common(o.kind == NoiseKind::binary ? "random_binary" : "gaussian", samples, o.channels, sample_time);
  out.description.json().update({{"amplitude", o.amplitude},
                                 {"clock_divider", o.clock_divider},
                                 {"channel_pattern", "independent"},
                                 {"channel_seeds", seeds},
                                 {"seed", o.seed}});
  return out;
}

Eigen::MatrixXd hadamard(int order) {
  if (order < 1 || (order & (order - 1)) != 0) fail("Hadamard matrix", "order must be a power of two", order);
  Eigen::MatrixXd H = Eigen::MatrixXd::Ones(1, 1);
  while (H.rows() < order) {
    const Eigen::Index r = H.rows();
    Eigen::MatrixXd next(2 * r, 2 * r);
    next << H, H, H, -H;
    H = std::move(next);
  }
  return H;
}

Excitation multisine(const MultisineOptions& o, double T) {
  const char* where = "multisine";
  require_common(where, T, o.channels);
  const Eigen::Index N = o.period_samples;
  if (N < 4) fail(where, "period_samples must be at least 4", static_cast<double>(N));
  if (o.periods < 1) fail(where, "periods must be at least 1", o.periods);
  if (!(o.level > 0.0) || !std::isfinite(o.level)) fail(where, "level must be positive", o.level);
  if (!(o.f_min >= 0.0) || !std::isfinite(o.f_min)) fail(where, "f_min must be >= 0", o.f_min);
  if (!(o.f_max >= o.f_min) || !std::isfinite(o.f_max))
    fail(where, "f_max must be finite and >= f_min = " + std::to_string(o.f_min), o.f_max);

  // Excited DFT lines: f_min <= k / (N T) <= f_max, 0 < k < N / 2.
  const double resolution = 1.0 / (static_cast<double>(N) * T);
  std::vector<Eigen::Index> lines;
  for (Eigen::Index k = 1; 2 * k < N; ++k) {
    const double f = static_cast<double>(k) * resolution;
    if (f >= o.f_min * (1 - 1e-12) && f <= o.f_max * (1 + 1e-12)) lines.push_back(k);
  }
  if (lines.empty()) {
    std::ostringstream msg;
    msg << "multisine: no DFT line in the band " << o.f_min << " .. " << o.f_max << " Hz (line spacing " << resolution
        << " Hz, Nyquist " << 0.5 / T << " Hz)";
    throw Error(msg.str());
  }

  std::mt19937_64 rng(o.seed);
  std::vector<std::complex<double>> spectrum(static_cast<std::size_t>(N));
  nlohmann::json amplitudes = nlohmann::json::array(), phases = nlohmann::json::array(),
                 frequencies = nlohmann::json::array();
  double power = 0.0;
  std::vector<double> a(lines.size()), phi(lines.size());
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const double f = static_cast<double>(lines[i]) * resolution;
    a[i] = o.amplitude_spectrum ? o.amplitude_spectrum(f) : 1.0;
    if (!(a[i] >= 0.0) || !std::isfinite(a[i]))
      fail(where, "amplitude_spectrum must be finite and non-negative at " + std::to_string(f) + " Hz", a[i]);
    phi[i] = kTwoPi * uniform01(rng);
    power += a[i] * a[i] / 2.0;
  }
  if (!(power > 0.0)) throw Error("multisine: amplitude_spectrum is zero on every excited line");

  // s[n] = sum A_k cos(2 pi k n / N + phi_k) by an inverse DFT.
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const std::complex<double> X = 0.5 * static_cast<double>(N) * std::polar(a[i], phi[i]);
    spectrum[static_cast<std::size_t>(lines[i])] = X;
    spectrum[static_cast<std::size_t>(N - lines[i])] = std::conj(X);
  }
  std::vector<std::complex<double>> time;
  Eigen::FFT<double> fft;
  fft.inv(time, spectrum);
  Eigen::VectorXd period(N);
  for (Eigen::Index n = 0; n < N; ++n) period(n) = time[static_cast<std::size_t>(n)].real();

  const double scale =
      o.normalisation == Normalisation::rms ? o.level / std::sqrt(power) : o.level / period.cwiseAbs().maxCoeff();
  period *= scale;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    amplitudes.push_back(a[i] * scale);
    phases.push_back(phi[i]);
    frequencies.push_back(static_cast<double>(lines[i]) * resolution);
  }

  int order = 1;
  Eigen::MatrixXd H = Eigen::MatrixXd::Ones(o.channels, 1);
  if (o.pattern == ChannelPattern::hadamard) {
    while (order < o.channels) order *= 2;
    if (o.periods % order != 0)
      fail(where,
           "with the hadamard pattern for " + std::to_string(o.channels) + " channels, periods must be a multiple of " +
               std::to_string(order),
           o.periods);
    H = hadamard(order).topRows(o.channels);
  }
  Excitation out;
  out.samples.resize(N * o.periods, o.channels);
  for (int p = 0; p < o.periods; ++p)
    for (int j = 0; j < o.channels; ++j) out.samples.block(p * N, j, N, 1) = H(j, p % H.cols()) * period;

  out.description.json() = common("multisine", N * o.periods, o.channels, T);
  out.description.json().update({{"normalisation", o.normalisation == Normalisation::rms ? "rms" : "peak"},
                                 {"level", o.level},
                                 {"rms", std::sqrt(period.squaredNorm() / static_cast<double>(N))},
                                 {"peak", period.cwiseAbs().maxCoeff()},
                                 {"period_samples", N},
                                 {"periods", o.periods},
                                 {"lines", lines},
                                 {"frequencies", frequencies},
                                 {"line_amplitudes", amplitudes},
                                 {"phases", phases},
                                 {"channel_pattern", o.pattern == ChannelPattern::hadamard ? "hadamard" : "identical"},
                                 {"seed", o.seed}});
  if (o.pattern == ChannelPattern::hadamard) {
    nlohmann::json rows = nlohmann::json::array();
    const Eigen::MatrixXd full = hadamard(order);
    for (Eigen::Index r = 0; r < full.rows(); ++r) {
      nlohmann::json row = nlohmann::json::array();
      for (Eigen::Index c = 0; c < full.cols(); ++c) row.push_back(static_cast<int>(full(r, c)));
      rows.push_back(row);
    }
    out.description.json()["hadamard"] = rows;
  }
  return out;
}

double chirp_frequency(const ChirpOptions& o, double duration, double t) {
  if (o.sweep == Sweep::linear) return o.f_start + (o.f_end - o.f_start) * t / duration;
  return o.f_start * std::pow(o.f_end / o.f_start, t / duration);
}

Excitation chirp(const ChirpOptions& o, Eigen::Index samples, double T) {
  const char* where = "chirp";
  require_common(where, T, o.channels);
  require_amplitude(where, o.amplitude);
  if (samples < 2) fail(where, "samples must be at least 2", static_cast<double>(samples));
  const double nyquist = 0.5 / T;
  for (const double f : {o.f_start, o.f_end})
    if (!(f >= 0.0) || !(f < nyquist))
      fail(where, "frequencies must lie in [0, Nyquist = " + std::to_string(nyquist) + " Hz)", f);
  if (o.sweep == Sweep::logarithmic && !(o.f_start > 0.0 && o.f_end > 0.0 && o.f_start != o.f_end))
    fail(where, "a logarithmic sweep needs distinct positive frequencies; f_start", o.f_start);
  const double D = static_cast<double>(samples) * T;
  const double rate = std::log(o.f_end / o.f_start) / D;
  Excitation out;
  out.samples.resize(samples, o.channels);
  for (Eigen::Index n = 0; n < samples; ++n) {
    const double t = static_cast<double>(n) * T;
    const double phase = o.sweep == Sweep::linear ? kTwoPi * (o.f_start * t + (o.f_end - o.f_start) * t * t / (2 * D))
                                                  : kTwoPi * o.f_start / rate * std::expm1(rate * t);
    out.samples.row(n).setConstant(o.amplitude * std::sin(phase));
  }
  out.description.json() = common("chirp", samples, o.channels, T);
  out.description.json().update({{"sweep", o.sweep == Sweep::linear ? "linear" : "logarithmic"},
                                 {"amplitude", o.amplitude},
                                 {"f_start", o.f_start},
                                 {"f_end", o.f_end},
                                 {"duration", D},
                                 {"channel_pattern", "identical"}});
  return out;
}

Excitation stepped_sine(const SteppedSineOptions& o, double T) {
  const char* where = "stepped sine";
  require_common(where, T, o.channels);
  require_amplitude(where, o.amplitude);
  if (o.frequencies.empty()) throw Error("stepped sine: no frequencies given");
  if (o.measure_periods < 1) fail(where, "measure_periods must be at least 1", o.measure_periods);
  if (!(o.settle_time >= 0.0) || !std::isfinite(o.settle_time))
    fail(where, "settle_time must be non-negative", o.settle_time);
  const auto settle = static_cast<Eigen::Index>(std::llround(o.settle_time / T));
  std::vector<Eigen::Index> measure;
  Eigen::Index total = 0;
  for (const double f : o.frequencies) {
    if (!(f > 0.0) || !(f < 0.5 / T))
      fail(where, "every frequency must lie in (0, Nyquist = " + std::to_string(0.5 / T) + " Hz)", f);
    const auto M = static_cast<Eigen::Index>(std::llround(o.measure_periods / (f * T)));
    if (M < 2 * o.measure_periods) fail(where, "frequency too close to Nyquist for whole periods", f);
    measure.push_back(M);
    total += settle + M;
  }
  Excitation out;
  out.samples.resize(total, o.channels);
  nlohmann::json steps = nlohmann::json::array();
  Eigen::Index start = 0;
  for (std::size_t i = 0; i < o.frequencies.size(); ++i) {
    const Eigen::Index M = measure[i];
    const double f = o.measure_periods / (static_cast<double>(M) * T);
    for (Eigen::Index n = 0; n < settle + M; ++n)
      out.samples.row(start + n).setConstant(o.amplitude * std::sin(kTwoPi * f * static_cast<double>(n) * T));
    steps.push_back({{"frequency_requested", o.frequencies[i]},
                     {"frequency", f},
                     {"start_sample", start},
                     {"settle_samples", settle},
                     {"measure_start_sample", start + settle},
                     {"measure_samples", M}});
    start += settle + M;
  }
  out.description.json() = common("stepped_sine", total, o.channels, T);
  out.description.json().update({{"amplitude", o.amplitude},
                                 {"settle_time", o.settle_time},
                                 {"measure_periods", o.measure_periods},
                                 {"steps", steps},
                                 {"channel_pattern", "identical"}});
  return out;
}

}  // namespace ambid::sim
