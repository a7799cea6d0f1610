#pragma once
// The messages on the bus as plain C++ values, independent of either DDS vendor. One struct per
// topic of idl/ambid.idl, same fields and meaning (see there); the backends convert. `limits`
// mirrors the IDL bounds (each backend static_asserts that); validate.hpp checks them.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace ambid::bus {

namespace limits {
inline constexpr std::size_t id_length = 64;
inline constexpr std::size_t name_length = 32;
inline constexpr std::size_t text_length = 256;
inline constexpr std::size_t max_channels = 16;
inline constexpr std::size_t max_batch_values = 8192;
inline constexpr std::size_t max_parameters = 64;
inline constexpr std::size_t max_matrix_values = 4096;
inline constexpr std::size_t max_frequencies = 2048;
inline constexpr std::size_t max_response_values = 16384;
inline constexpr std::size_t max_peaks = 16;
}  // namespace limits

// Values as in ROS diagnostic_msgs/DiagnosticStatus.
enum class AlertLevel : std::uint8_t { ok = 0, warn = 1, error = 2, stale = 3 };
enum class SourceKind : std::uint8_t { sim, replay, rig };
enum class IsoZone : std::uint8_t { none, a, b, c, d };

struct NamedValue {
  std::string name;
  double value = 0.0;
  bool operator==(const NamedValue&) const = default;
};

struct Estimate {
  std::string name;
  double value = 0.0;
  double sigma = 0.0;  // one standard deviation
  bool operator==(const Estimate&) const = default;
};

struct Matrix {
  std::uint32_t rows = 0;
  std::uint32_t cols = 0;
  std::vector<double> values;  // row-major, rows * cols entries
  bool operator==(const Matrix&) const = default;
};

struct StateSpace {
  Matrix a, b, c, d;
  bool operator==(const StateSpace&) const = default;
};

struct PlantSamples {
  std::string plant_id;
  std::uint64_t seq = 0;
  double t0 = 0.0;
  double sample_time = 0.0;
  std::uint32_t count = 0;
  std::string description_id;  // the PlantDescription these samples belong to
  std::vector<std::string> y_names, u_names, r_names;
  std::vector<double> y, u, r;  // row-major: count x names.size()
  bool operator==(const PlantSamples&) const = default;
};

struct ControllerDescription {
  std::string kind;
  double sample_time = 0.0;
  std::vector<std::string> inputs, outputs;
  StateSpace matrices;
  Matrix initial_state;                // states x 1, or 0 x 0 for zero
  Matrix output_limits, state_limits;  // n x 2 of [lo, hi]; 0 x 2 when none
  bool operator==(const ControllerDescription&) const = default;
};

struct PlantDescription {
  std::string plant_id;
  std::string description_id;  // hash of the content (services/convert/plant_description.hpp)
  std::string model;
  std::vector<NamedValue> parameters;  // nominal
  double sample_time = 0.0;
  std::vector<std::string> y_names, u_names, r_names;
  std::vector<NamedValue> operating_point;
  bool has_controller = false;
  ControllerDescription controller;
  bool operator==(const PlantDescription&) const = default;
};

struct ExcitationCommand {
  std::string plant_id;
  std::uint64_t seq = 0;
  std::string kind;
  std::vector<std::string> channels;
  double amplitude = 0.0;
  double duration = 0.0;
  std::uint64_t seed = 0;
  std::vector<NamedValue> settings;
  std::vector<double> frequencies;
  bool operator==(const ExcitationCommand&) const = default;
};

struct PlantSourceCommand {
  std::string plant_id;
  std::uint64_t seq = 0;
  SourceKind kind = SourceKind::sim;
  std::string target;
  bool operator==(const PlantSourceCommand&) const = default;
};

struct PlantSourceState {
  std::string plant_id;
  double time = 0.0;
  SourceKind kind = SourceKind::sim;
  std::string target;
  std::uint64_t command_seq = 0;
  bool command_accepted = true;
  std::string message;
  bool operator==(const PlantSourceState&) const = default;
};

struct IdentifiedModel {
  std::string plant_id;
  std::uint64_t seq = 0;
  double time = 0.0;
  double window = 0.0;
  std::string plant_model;
  std::string method;
  double sample_time = 0.0;
  StateSpace discrete;
  StateSpace continuous;
  std::vector<Estimate> parameters;
  std::vector<Estimate> physical;
  std::vector<NamedValue> nrmse;
  bool operator==(const IdentifiedModel&) const = default;
};

struct SensitivityPeak {
  std::string output;
  double frequency = 0.0;
  double magnitude = 0.0;
  IsoZone zone = IsoZone::none;
  bool operator==(const SensitivityPeak&) const = default;
};

struct FrequencyResponse {
  std::string plant_id;
  std::string kind;
  std::uint64_t seq = 0;
  double time = 0.0;
  std::vector<std::string> outputs, inputs;
  std::vector<double> frequencies;
  std::vector<double> re, im;  // [(i * inputs.size() + j) * frequencies.size() + k]
  std::vector<SensitivityPeak> peaks;
  IsoZone zone = IsoZone::none;
  bool operator==(const FrequencyResponse&) const = default;
};

struct Alert {
  std::string plant_id;
  std::string fault;
  std::int32_t channel = 0;  // 1-based; 0: not channel specific
  double time = 0.0;
  AlertLevel level = AlertLevel::ok;
  std::string parameter;
  double value = 0.0;
  double baseline = 0.0;
  std::string message;
  bool operator==(const Alert&) const = default;
};

struct Health {
  std::string node;
  std::string role;
  double time = 0.0;
  AlertLevel level = AlertLevel::ok;
  std::string message;
  std::uint64_t received = 0;
  std::uint64_t published = 0;
  std::uint64_t errors = 0;
  bool operator==(const Health&) const = default;
};

}  // namespace ambid::bus
