#include "dds/messages.hpp"

#include <string>
#include <vector>

namespace ambid::bus::test {
namespace messages_support {

std::vector<double> ramp(std::size_t n, double start) {
  std::vector<double> v(n);
  for (std::size_t i = 0; i < n; ++i) v[i] = start + 0.25 * static_cast<double>(i);
  return v;
}

std::vector<std::string> names(std::size_t n, char first) {
  std::vector<std::string> v;
  for (std::size_t i = 0; i < n; ++i) {
    v.push_back(text_of_length(limits::name_length, static_cast<char>(first + i % 20)));
  }
  return v;
}

template <class Named>
std::vector<Named> named_list(std::size_t n, char first) {
  std::vector<Named> v(n);
  for (std::size_t i = 0; i < n; ++i) {
    v[i].name = text_of_length(limits::name_length, static_cast<char>(first + i % 20));
    v[i].value = 1.5 * static_cast<double>(i) - 7.0;
  }
  return v;
}

Matrix square(std::size_t n, double start) {
  return {static_cast<std::uint32_t>(n), static_cast<std::uint32_t>(n), ramp(n * n, start)};
}

}  // namespace messages_support
using namespace messages_support;

std::string text_of_length(std::size_t n, char first) {
  // Printable ASCII '!'..'~', cycling.
  std::string s(n, ' ');
  for (std::size_t i = 0; i < n; ++i) {
    s[i] = static_cast<char>('!' + (static_cast<std::size_t>(first - '!') + i) % 94);
  }
  return s;
}

template <>
PlantSamples largest<PlantSamples>() {
  const std::size_t count = limits::max_batch_values / limits::max_channels;
  return {.plant_id = text_of_length(limits::id_length),
          .seq = 0xFFFF'FFFF'FFFF'FFF0u,
          .t0 = 12.5,
          .sample_time = 1e-4,
          .count = static_cast<std::uint32_t>(count),
          .description_id = text_of_length(limits::id_length, 'D'),
          .y_names = names(limits::max_channels, 'a'),
          .u_names = names(limits::max_channels, 'b'),
          .r_names = names(limits::max_channels, 'c'),
          .y = ramp(limits::max_batch_values, 1.0),
          .u = ramp(limits::max_batch_values, -1.0),
          .r = ramp(limits::max_batch_values, 1e-3)};
}

template <>
PlantSamples small<PlantSamples>(int k) {
  return {.plant_id = "bearing-A",
          .seq = static_cast<std::uint64_t>(k),
          .t0 = 0.01 * k,
          .sample_time = 1e-4,
          .count = 2,
          .description_id = "0123456789abcdef",
          .y_names = {"x", "i1", "i2"},
          .u_names = {"u1", "u2"},
          .r_names = {},
          .y = {1e-6 * k, 0.5, 0.5, 2e-6, 0.51, 0.49},
          .u = {8.75, 8.75, 8.8, 8.7},
          .r = {}};
}

template <>
PlantDescription largest<PlantDescription>() {
  const std::size_t n = 64;  // 64 x 64 = max_matrix_values
  return {.plant_id = text_of_length(limits::id_length),
          .description_id = text_of_length(limits::id_length, 'd'),
          .model = text_of_length(limits::name_length, 'm'),
          .parameters = named_list<NamedValue>(limits::max_parameters, 'p'),
          .sample_time = 1e-4,
          .y_names = names(limits::max_channels, 'y'),
          .u_names = names(limits::max_channels, 'u'),
          .r_names = names(limits::max_channels, 'r'),
          .operating_point = named_list<NamedValue>(limits::max_parameters, 'o'),
          .has_controller = true,
          .controller = {.kind = text_of_length(limits::name_length, 'k'),
                         .sample_time = 2e-4,
                         .inputs = names(limits::max_channels, 'i'),
                         .outputs = names(limits::max_channels, 'O'),
                         .matrices = {square(n, 1.0), square(n, 2.0), square(n, 3.0), square(n, 4.0)},
                         .initial_state = {static_cast<std::uint32_t>(limits::max_matrix_values), 1,
                                           ramp(limits::max_matrix_values, -5.0)},
                         .output_limits = {2048, 2, ramp(limits::max_matrix_values, -9.0)},
                         .state_limits = {2048, 2, ramp(limits::max_matrix_values, 9.0)}}};
}

template <>
PlantDescription small<PlantDescription>(int k) {
  return {.plant_id = "bearing-A",
          .description_id = "description-" + std::to_string(k),
          .model = "amb1dof_voltage",
          .parameters = {{"R1", 17.5 + k}, {"m", 1.8}},
          .sample_time = 1e-4,
          .y_names = {"x", "i1", "i2"},
          .u_names = {"u1", "u2"},
          .r_names = {"r1", "r2"},
          .operating_point = {{"u1", 8.75}},
          .has_controller = k % 2 == 1,
          .controller = {.kind = "state_space",
                         .sample_time = 1e-4,
                         .inputs = {"x"},
                         .outputs = {"u1"},
                         .matrices = {{1, 1, {0.5}}, {1, 1, {1.0}}, {1, 1, {-2.0}}, {1, 1, {0.0}}},
                         .initial_state = {},
                         .output_limits = {1, 2, {0.0, 10.5}},
                         .state_limits = {0, 2, {}}}};
}

template <>
ExcitationCommand largest<ExcitationCommand>() {
  return {.plant_id = text_of_length(limits::id_length),
          .seq = 7,
          .kind = text_of_length(limits::name_length, 'k'),
          .channels = names(limits::max_channels, 'r'),
          .amplitude = 0.2,
          .duration = 30.0,
          .seed = 0xDEAD'BEEF'0000'0001u,
          .settings = named_list<NamedValue>(limits::max_parameters, 's'),
          .frequencies = ramp(limits::max_frequencies, 1.0)};
}

template <>
ExcitationCommand small<ExcitationCommand>(int k) {
  return {.plant_id = "bearing-A",
          .seq = static_cast<std::uint64_t>(k),
          .kind = "multisine",
          .channels = {"r1"},
          .amplitude = 0.1 * k,
          .duration = 0.0,
          .seed = 42,
          .settings = {{"f_min", 1.0}, {"f_max", 400.0}},
          .frequencies = {}};
}

template <>
PlantSourceCommand largest<PlantSourceCommand>() {
  return {.plant_id = text_of_length(limits::id_length),
          .seq = 99,
          .kind = SourceKind::rig,
          .target = text_of_length(limits::text_length, 'A')};
}

template <>
PlantSourceCommand small<PlantSourceCommand>(int k) {
  return {.plant_id = "bearing-A",
          .seq = static_cast<std::uint64_t>(k),
          .kind = SourceKind::replay,
          .target = "runs/run" + std::to_string(k) + ".json"};
}

template <>
PlantSourceState largest<PlantSourceState>() {
  return {.plant_id = text_of_length(limits::id_length),
          .time = 1e9,
          .kind = SourceKind::rig,
          .target = text_of_length(limits::text_length, 'B'),
          .command_seq = 99,
          .command_accepted = false,
          .message = text_of_length(limits::text_length, 'C')};
}

template <>
PlantSourceState small<PlantSourceState>(int k) {
  return {.plant_id = "bearing-A",
          .time = 1.0 * k,
          .kind = SourceKind::sim,
          .target = "",
          .command_seq = static_cast<std::uint64_t>(k),
          .command_accepted = true,
          .message = "running"};
}

template <>
IdentifiedModel largest<IdentifiedModel>() {
  const std::size_t n = 64;  // 64 x 64 = max_matrix_values
  return {.plant_id = text_of_length(limits::id_length),
          .seq = 3,
          .time = 60.0,
          .window = 10.0,
          .plant_model = text_of_length(limits::name_length, 'p'),
          .method = text_of_length(limits::name_length, 'm'),
          .sample_time = 1e-4,
          .discrete = {square(n, 1.0), square(n, 2.0), square(n, 3.0), square(n, 4.0)},
          .continuous = {square(n, -1.0), square(n, -2.0), square(n, -3.0), square(n, -4.0)},
          .parameters = named_list<Estimate>(limits::max_parameters, 'v'),
          .physical = named_list<Estimate>(limits::max_parameters, 'P'),
          .nrmse = named_list<NamedValue>(limits::max_channels, 'n')};
}

template <>
IdentifiedModel small<IdentifiedModel>(int k) {
  return {.plant_id = "bearing-A",
          .seq = static_cast<std::uint64_t>(k),
          .time = 10.0 * k,
          .window = 10.0,
          .plant_model = "amb1dof_voltage",
          .method = "deadbeat",
          .sample_time = 1e-4,
          .discrete = {{1, 1, {0.99}}, {1, 2, {0.1, 0.2}}, {1, 1, {1.0}}, {1, 2, {0.0, 0.0}}},
          .continuous = {},
          .parameters = {{"v5", 40.7925, 0.02}},
          .physical = {{"R1", 17.5 + k, 0.009}},
          .nrmse = {{"x", 0.01}}};
}

template <>
FrequencyResponse largest<FrequencyResponse>() {
  // 2 outputs x 4 inputs x 2048 frequencies = max_response_values
  return {.plant_id = text_of_length(limits::id_length),
          .kind = text_of_length(limits::name_length, 'S'),
          .seq = 11,
          .time = 120.0,
          .outputs = names(2, 'o'),
          .inputs = names(4, 'i'),
          .frequencies = ramp(limits::max_frequencies, 0.5),
          .re = ramp(limits::max_response_values, 0.0),
          .im = ramp(limits::max_response_values, -100.0),
          .peaks = std::vector<SensitivityPeak>(limits::max_peaks,
                                                {text_of_length(limits::name_length, 'q'), 210.0, 3.5, IsoZone::b}),
          .zone = IsoZone::d};
}

template <>
FrequencyResponse small<FrequencyResponse>(int k) {
  return {.plant_id = "bearing-A",
          .kind = "sensitivity",
          .seq = static_cast<std::uint64_t>(k),
          .time = 1.0 * k,
          .outputs = {"x"},
          .inputs = {"r1"},
          .frequencies = {10.0, 100.0},
          .re = {1.0, 1.2},
          .im = {0.0, -0.3},
          .peaks = {{"x", 210.0, 2.9, IsoZone::a}},
          .zone = IsoZone::a};
}

template <>
Alert largest<Alert>() {
  return {.plant_id = text_of_length(limits::id_length),
          .fault = text_of_length(limits::name_length, 'f'),
          .channel = -2147483647,
          .time = 12.5,
          .level = AlertLevel::stale,
          .parameter = text_of_length(limits::name_length, 'R'),
          .value = 21.0,
          .baseline = 17.5,
          .message = text_of_length(limits::text_length, 'M')};
}

template <>
Alert small<Alert>(int k) {
  return {.plant_id = "bearing-A",
          .fault = "coil_resistance",
          .channel = 1,
          .time = 12.5 + k,
          .level = AlertLevel::warn,
          .parameter = "R1",
          .value = 21.0 + k,
          .baseline = 17.5,
          .message = "coil 1 resistance 20 % above baseline"};
}

template <>
Health largest<Health>() {
  return {.node = text_of_length(limits::id_length),
          .role = text_of_length(limits::name_length, 'r'),
          .time = 3.25,
          .level = AlertLevel::error,
          .message = text_of_length(limits::text_length, 'H'),
          .received = 0xFFFF'FFFF'FFFF'FFFFu,
          .published = 1,
          .errors = 2};
}

template <>
Health small<Health>(int k) {
  return {.node = "identifier@host",
          .role = "identifier",
          .time = 1.0 * k,
          .level = AlertLevel::ok,
          .message = "",
          .received = static_cast<std::uint64_t>(100 * k),
          .published = static_cast<std::uint64_t>(k),
          .errors = 0};
}

}  // namespace ambid::bus::test
