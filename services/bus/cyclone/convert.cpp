#include "services/bus/cyclone/convert.hpp"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace ambid::bus::cyclone {
namespace {

static_assert(limits::id_length == ambid_ID_LENGTH);
static_assert(limits::name_length == ambid_NAME_LENGTH);
static_assert(limits::text_length == ambid_TEXT_LENGTH);
static_assert(limits::max_channels == ambid_MAX_CHANNELS);
static_assert(limits::max_batch_values == ambid_MAX_BATCH_VALUES);
static_assert(limits::max_parameters == ambid_MAX_PARAMETERS);
static_assert(limits::max_matrix_values == ambid_MAX_MATRIX_VALUES);
static_assert(limits::max_frequencies == ambid_MAX_FREQUENCIES);
static_assert(limits::max_response_values == ambid_MAX_RESPONSE_VALUES);
static_assert(limits::max_peaks == ambid_MAX_PEAKS);
static_assert(static_cast<int>(AlertLevel::stale) == ambid_LEVEL_STALE);
static_assert(static_cast<int>(SourceKind::rig) == ambid_SOURCE_RIG);
static_assert(static_cast<int>(IsoZone::d) == ambid_ZONE_D);

// Same enumerators in the same order (asserted above).
template <class To, class From>
To enum_cast(From value) {
  return static_cast<To>(static_cast<int>(value));
}

template <std::size_t N>
void copy(const std::string& in, char (&out)[N]) {
  if (in.size() >= N) throw std::logic_error("unvalidated string reached the Cyclone backend");
  std::memcpy(out, in.data(), in.size());
  out[in.size()] = '\0';
}

template <std::size_t N>
std::string text(const char (&in)[N]) {
  return std::string(in, strnlen(in, N));
}

// Gives the sequence a buffer of n elements that dds_sample_free releases.
template <class Sequence>
auto* allocate(Sequence& seq, std::size_t n) {
  using Element = std::remove_pointer_t<decltype(seq._buffer)>;
  seq._maximum = seq._length = static_cast<std::uint32_t>(n);
  seq._buffer = n == 0 ? nullptr : static_cast<Element*>(dds_alloc(n * sizeof(Element)));
  seq._release = true;
  return seq._buffer;
}

void put(dds_sequence_double& seq, const std::vector<double>& in) {
  std::copy(in.begin(), in.end(), allocate(seq, in.size()));
}

void put(dds_sequence_ambid_Name& seq, const std::vector<std::string>& in) {
  auto* out = allocate(seq, in.size());
  for (std::size_t i = 0; i < in.size(); ++i) copy(in[i], out[i]);
}

void put(dds_sequence_ambid_NamedValue& seq, const std::vector<NamedValue>& in) {
  auto* out = allocate(seq, in.size());
  for (std::size_t i = 0; i < in.size(); ++i) {
    copy(in[i].name, out[i].name);
    out[i].value = in[i].value;
  }
}

void put(dds_sequence_ambid_Estimate& seq, const std::vector<Estimate>& in) {
  auto* out = allocate(seq, in.size());
  for (std::size_t i = 0; i < in.size(); ++i) {
    copy(in[i].name, out[i].name);
    out[i].value = in[i].value;
    out[i].sigma = in[i].sigma;
  }
}

void put(ambid_Matrix& out, const Matrix& in) {
  out.rows = in.rows;
  out.cols = in.cols;
  put(out.values, in.values);
}

void put(ambid_StateSpace& out, const StateSpace& in) {
  put(out.a, in.a);
  put(out.b, in.b);
  put(out.c, in.c);
  put(out.d, in.d);
}

std::vector<double> doubles(const dds_sequence_double& in) { return {in._buffer, in._buffer + in._length}; }

std::vector<std::string> names(const dds_sequence_ambid_Name& in) {
  std::vector<std::string> out;
  out.reserve(in._length);
  for (std::uint32_t i = 0; i < in._length; ++i) out.push_back(text(in._buffer[i]));
  return out;
}

std::vector<NamedValue> named_values(const dds_sequence_ambid_NamedValue& in) {
  std::vector<NamedValue> out;
  out.reserve(in._length);
  for (std::uint32_t i = 0; i < in._length; ++i) {
    out.push_back({text(in._buffer[i].name), in._buffer[i].value});
  }
  return out;
}

std::vector<Estimate> estimates(const dds_sequence_ambid_Estimate& in) {
  std::vector<Estimate> out;
  out.reserve(in._length);
  for (std::uint32_t i = 0; i < in._length; ++i) {
    out.push_back({text(in._buffer[i].name), in._buffer[i].value, in._buffer[i].sigma});
  }
  return out;
}

Matrix matrix(const ambid_Matrix& in) { return {in.rows, in.cols, doubles(in.values)}; }

StateSpace state_space(const ambid_StateSpace& in) { return {matrix(in.a), matrix(in.b), matrix(in.c), matrix(in.d)}; }

}  // namespace

void to_cyclone(const PlantSamples& in, ambid_PlantSamples& out) {
  copy(in.plant_id, out.plant_id);
  out.seq = in.seq;
  out.t0 = in.t0;
  out.sample_time = in.sample_time;
  out.count = in.count;
  copy(in.description_id, out.description_id);
  put(out.y_names, in.y_names);
  put(out.u_names, in.u_names);
  put(out.r_names, in.r_names);
  put(out.y, in.y);
  put(out.u, in.u);
  put(out.r, in.r);
}

PlantSamples from_cyclone(const ambid_PlantSamples& in) {
  return {.plant_id = text(in.plant_id),
          .seq = in.seq,
          .t0 = in.t0,
          .sample_time = in.sample_time,
          .count = in.count,
          .description_id = text(in.description_id),
          .y_names = names(in.y_names),
          .u_names = names(in.u_names),
          .r_names = names(in.r_names),
          .y = doubles(in.y),
          .u = doubles(in.u),
          .r = doubles(in.r)};
}

void to_cyclone(const PlantDescription& in, ambid_PlantDescription& out) {
  copy(in.plant_id, out.plant_id);
  copy(in.description_id, out.description_id);
  copy(in.model, out.model);
  put(out.parameters, in.parameters);
  out.sample_time = in.sample_time;
  put(out.y_names, in.y_names);
  put(out.u_names, in.u_names);
  put(out.r_names, in.r_names);
  put(out.operating_point, in.operating_point);
  out.has_controller = in.has_controller;
  const ControllerDescription& c = in.controller;
  copy(c.kind, out.controller.kind);
  out.controller.sample_time = c.sample_time;
  put(out.controller.inputs, c.inputs);
  put(out.controller.outputs, c.outputs);
  put(out.controller.matrices, c.matrices);
  put(out.controller.initial_state, c.initial_state);
  put(out.controller.output_limits, c.output_limits);
  put(out.controller.state_limits, c.state_limits);
}

PlantDescription from_cyclone(const ambid_PlantDescription& in) {
  const ambid_ControllerDescription& c = in.controller;
  return {.plant_id = text(in.plant_id),
          .description_id = text(in.description_id),
          .model = text(in.model),
          .parameters = named_values(in.parameters),
          .sample_time = in.sample_time,
          .y_names = names(in.y_names),
          .u_names = names(in.u_names),
          .r_names = names(in.r_names),
          .operating_point = named_values(in.operating_point),
          .has_controller = in.has_controller,
          .controller = {.kind = text(c.kind),
                         .sample_time = c.sample_time,
                         .inputs = names(c.inputs),
                         .outputs = names(c.outputs),
                         .matrices = state_space(c.matrices),
                         .initial_state = matrix(c.initial_state),
                         .output_limits = matrix(c.output_limits),
                         .state_limits = matrix(c.state_limits)}};
}

void to_cyclone(const ExcitationCommand& in, ambid_ExcitationCommand& out) {
  copy(in.plant_id, out.plant_id);
  out.seq = in.seq;
  copy(in.kind, out.kind);
  put(out.channels, in.channels);
  out.amplitude = in.amplitude;
  out.duration = in.duration;
  out.seed = in.seed;
  put(out.settings, in.settings);
  put(out.frequencies, in.frequencies);
}

ExcitationCommand from_cyclone(const ambid_ExcitationCommand& in) {
  return {.plant_id = text(in.plant_id),
          .seq = in.seq,
          .kind = text(in.kind),
          .channels = names(in.channels),
          .amplitude = in.amplitude,
          .duration = in.duration,
          .seed = in.seed,
          .settings = named_values(in.settings),
          .frequencies = doubles(in.frequencies)};
}

void to_cyclone(const PlantSourceCommand& in, ambid_PlantSourceCommand& out) {
  copy(in.plant_id, out.plant_id);
  out.seq = in.seq;
  out.kind = enum_cast<ambid_SourceKind>(in.kind);
  copy(in.target, out.target);
}

PlantSourceCommand from_cyclone(const ambid_PlantSourceCommand& in) {
  return {
      .plant_id = text(in.plant_id), .seq = in.seq, .kind = enum_cast<SourceKind>(in.kind), .target = text(in.target)};
}

void to_cyclone(const PlantSourceState& in, ambid_PlantSourceState& out) {
  copy(in.plant_id, out.plant_id);
  out.time = in.time;
  out.kind = enum_cast<ambid_SourceKind>(in.kind);
  copy(in.target, out.target);
  out.command_seq = in.command_seq;
  out.command_accepted = in.command_accepted;
  copy(in.message, out.message);
}

PlantSourceState from_cyclone(const ambid_PlantSourceState& in) {
  return {.plant_id = text(in.plant_id),
          .time = in.time,
          .kind = enum_cast<SourceKind>(in.kind),
          .target = text(in.target),
          .command_seq = in.command_seq,
          .command_accepted = in.command_accepted,
          .message = text(in.message)};
}

void to_cyclone(const IdentifiedModel& in, ambid_IdentifiedModel& out) {
  copy(in.plant_id, out.plant_id);
  out.seq = in.seq;
  out.time = in.time;
  out.window = in.window;
  copy(in.plant_model, out.plant_model);
  copy(in.method, out.method);
  out.sample_time = in.sample_time;
  put(out.discrete, in.discrete);
  put(out.continuous, in.continuous);
  put(out.parameters, in.parameters);
  put(out.physical, in.physical);
  put(out.nrmse, in.nrmse);
}

IdentifiedModel from_cyclone(const ambid_IdentifiedModel& in) {
  return {.plant_id = text(in.plant_id),
          .seq = in.seq,
          .time = in.time,
          .window = in.window,
          .plant_model = text(in.plant_model),
          .method = text(in.method),
          .sample_time = in.sample_time,
          .discrete = state_space(in.discrete),
          .continuous = state_space(in.continuous),
          .parameters = estimates(in.parameters),
          .physical = estimates(in.physical),
          .nrmse = named_values(in.nrmse)};
}

void to_cyclone(const FrequencyResponse& in, ambid_FrequencyResponse& out) {
  copy(in.plant_id, out.plant_id);
  copy(in.kind, out.kind);
  out.seq = in.seq;
  out.time = in.time;
  put(out.outputs, in.outputs);
  put(out.inputs, in.inputs);
  put(out.frequencies, in.frequencies);
  put(out.re, in.re);
  put(out.im, in.im);
  auto* peaks = allocate(out.peaks, in.peaks.size());
  for (std::size_t i = 0; i < in.peaks.size(); ++i) {
    copy(in.peaks[i].output, peaks[i].output);
    peaks[i].frequency = in.peaks[i].frequency;
    peaks[i].magnitude = in.peaks[i].magnitude;
    peaks[i].zone = enum_cast<ambid_IsoZone>(in.peaks[i].zone);
  }
  out.zone = enum_cast<ambid_IsoZone>(in.zone);
}

FrequencyResponse from_cyclone(const ambid_FrequencyResponse& in) {
  std::vector<SensitivityPeak> peaks;
  peaks.reserve(in.peaks._length);
  for (std::uint32_t i = 0; i < in.peaks._length; ++i) {
    const auto& p = in.peaks._buffer[i];
    peaks.push_back({text(p.output), p.frequency, p.magnitude, enum_cast<IsoZone>(p.zone)});
  }
  return {.plant_id = text(in.plant_id),
          .kind = text(in.kind),
          .seq = in.seq,
          .time = in.time,
          .outputs = names(in.outputs),
          .inputs = names(in.inputs),
          .frequencies = doubles(in.frequencies),
          .re = doubles(in.re),
          .im = doubles(in.im),
          .peaks = std::move(peaks),
          .zone = enum_cast<IsoZone>(in.zone)};
}

void to_cyclone(const Alert& in, ambid_Alert& out) {
  copy(in.plant_id, out.plant_id);
  copy(in.fault, out.fault);
  out.channel = in.channel;
  out.time = in.time;
  out.level = enum_cast<ambid_AlertLevel>(in.level);
  copy(in.parameter, out.parameter);
  out.value = in.value;
  out.baseline = in.baseline;
  copy(in.message, out.message);
}

Alert from_cyclone(const ambid_Alert& in) {
  return {.plant_id = text(in.plant_id),
          .fault = text(in.fault),
          .channel = in.channel,
          .time = in.time,
          .level = enum_cast<AlertLevel>(in.level),
          .parameter = text(in.parameter),
          .value = in.value,
          .baseline = in.baseline,
          .message = text(in.message)};
}

void to_cyclone(const Health& in, ambid_Health& out) {
  copy(in.node, out.node);
  copy(in.role, out.role);
  out.time = in.time;
  out.level = enum_cast<ambid_AlertLevel>(in.level);
  copy(in.message, out.message);
  out.received = in.received;
  out.published = in.published;
  out.errors = in.errors;
}

Health from_cyclone(const ambid_Health& in) {
  return {.node = text(in.node),
          .role = text(in.role),
          .time = in.time,
          .level = enum_cast<AlertLevel>(in.level),
          .message = text(in.message),
          .received = in.received,
          .published = in.published,
          .errors = in.errors};
}

}  // namespace ambid::bus::cyclone
