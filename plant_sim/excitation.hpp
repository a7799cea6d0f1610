#pragma once
// Excitation signals for closed-loop identification, reproducible from an explicit seed
// (std::mt19937_64; random numbers are mapped to uniforms and normals by ambid's own formulas,
// so the same seed gives bit-identical signals on every standard library).
//
// Every generator returns the samples (one row per sample, one column per channel; values are
// deviations, added to the controller output as r) and a JSON description that the runner
// writes into the experiment sidecar under "excitation". Common keys: "kind", "channels",
// "samples", "sample_time", "seed" (where used), "channel_pattern"; kind-specific keys are
// listed at each generator.
#include <cstdint>
#include <functional>
#include <vector>

#include <Eigen/Core>

#include "core/json_value.hpp"

namespace ambid::sim {

struct Excitation {
  Eigen::MatrixXd samples;  // samples x channels
  JsonValue description;
};

// Maximal-length PRBS from a Fibonacci LFSR with a primitive feedback polynomial, register
// length 2..32, period 2^n - 1 register clocks; each clock is held for clock_divider samples;
// values +amplitude / -amplitude. Channel j starts from register state shifted by
// j * period / channels clocks plus a seeded random offset common to all channels, so the
// channels are distinct, evenly spaced shifts of one m-sequence.
// Description: kind "prbs", amplitude, register_length, clock_divider, period_samples
// (= (2^n - 1) * clock_divider), periods (samples / period_samples, may be fractional),
// channel_pattern "shifted", channel_shifts (clocks), seed.
struct PrbsOptions {
  int register_length = 10;
  int clock_divider = 1;
  double amplitude = 1.0;
  std::uint64_t seed = 1;
  int channels = 1;
};
Excitation prbs(const PrbsOptions& options, Eigen::Index samples, double sample_time);

// Independent white signals, one seed per channel (derived from `seed`): binary +-amplitude
// (held for clock_divider samples) or Gaussian with standard deviation `amplitude`.
// Description: kind "random_binary" | "gaussian", amplitude, clock_divider,
// channel_pattern "independent", channel_seeds, seed.
enum class NoiseKind { binary, gaussian };
struct RandomOptions {
  NoiseKind kind = NoiseKind::binary;
  int clock_divider = 1;
  double amplitude = 1.0;
  std::uint64_t seed = 1;
  int channels = 1;
};
Excitation random_signal(const RandomOptions& options, Eigen::Index samples, double sample_time);

// Random-phase multisine, periodic with period_samples samples:
//   s[n] = sum_k A_k cos(2 pi k n / N + phi_k),  k over the excited DFT lines
// (every line with f_min <= k / (N T) <= f_max, 0 < k < N/2), phi_k uniform in [0, 2 pi) from
// the seed, A_k = amplitude_spectrum(f_k) (flat when empty), then scaled so the rms (or the
// peak |s| over one period) equals `level`. `periods` whole periods are generated.
// Channels: pattern `identical` puts s on every channel; `hadamard` multiplies channel j in
// period p by H(j, p mod P), H the Sylvester-Hadamard matrix of order P = smallest power of two
// >= channels (periods must be a multiple of P), so the FRF from each input can be separated
// from one record (rows of H are orthogonal over every P-period block).
// Description: kind "multisine", normalisation "rms" | "peak", level, rms, peak,
// period_samples, periods, lines (DFT indices within one period), frequencies (Hz),
// line_amplitudes, phases, channel_pattern "identical" | "hadamard", hadamard (P x P, when
// hadamard), seed.
enum class Normalisation { rms, peak };
enum class ChannelPattern { identical, hadamard };
struct MultisineOptions {
  double f_min = 0.0;
  double f_max = 0.0;
  Eigen::Index period_samples = 0;
  int periods = 1;
  double level = 1.0;
  Normalisation normalisation = Normalisation::rms;
  std::function<double(double)> amplitude_spectrum;  // relative amplitude at f (Hz); >= 0
  std::uint64_t seed = 1;
  int channels = 1;
  ChannelPattern pattern = ChannelPattern::identical;
};
Excitation multisine(const MultisineOptions& options, double sample_time);

// Swept sine a sin(phi(t)), t = n T, n = 0..samples-1, duration D = samples T, from f_start to
// f_end (Hz): linear   phi = 2 pi (f0 t + (f1 - f0) t^2 / (2 D)),
//             log      phi = 2 pi f0 D / ln(f1/f0) (exp(t ln(f1/f0) / D) - 1)  (f0, f1 > 0).
// Same signal on every channel. Description: kind "chirp", sweep "linear" | "logarithmic",
// amplitude, f_start, f_end, duration.
enum class Sweep { linear, logarithmic };
struct ChirpOptions {
  double f_start = 1.0;
  double f_end = 100.0;
  double amplitude = 1.0;
  Sweep sweep = Sweep::linear;
  int channels = 1;
};
Excitation chirp(const ChirpOptions& options, Eigen::Index samples, double sample_time);
// The instantaneous frequency (Hz) d phi/dt / (2 pi) of that chirp at time t.
double chirp_frequency(const ChirpOptions& options, double duration, double t);

// Stepped sine: for each requested frequency f, a settle segment of round(settle_time / T)
// samples followed by a measurement segment of M = round(measure_periods / (f T)) samples that
// holds exactly measure_periods whole periods of the snapped frequency
// f' = measure_periods / (M T) (the phase runs on continuously into the measurement segment;
// the signal starts at phase 0 in each step). Same signal on every channel.
// Description: kind "stepped_sine", amplitude, settle_time, measure_periods, steps: list of
// { frequency_requested, frequency, start_sample, settle_samples, measure_start_sample,
//   measure_samples }.
struct SteppedSineOptions {
  std::vector<double> frequencies;  // Hz, each 0 < f < 1 / (2 T)
  int measure_periods = 10;
  double settle_time = 0.0;  // s
  double amplitude = 1.0;
  int channels = 1;
};
Excitation stepped_sine(const SteppedSineOptions& options, double sample_time);

// Sylvester-Hadamard matrix of order `order` (a power of two), entries +-1, H H' = order I.
Eigen::MatrixXd hadamard(int order);

}  // namespace ambid::sim
