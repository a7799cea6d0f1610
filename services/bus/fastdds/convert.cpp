#include "services/bus/fastdds/convert.hpp"

#include <cstdint>
#include <string>
#include <type_traits>
#include <vector>

namespace ambid::bus::fastdds {
namespace {

using eprosima::fastrtps::fixed_string;

static_assert(limits::id_length == ::ambid::ID_LENGTH);
static_assert(limits::name_length == ::ambid::NAME_LENGTH);
static_assert(limits::text_length == ::ambid::TEXT_LENGTH);
static_assert(limits::max_channels == ::ambid::MAX_CHANNELS);
static_assert(limits::max_batch_values == ::ambid::MAX_BATCH_VALUES);
static_assert(limits::max_parameters == ::ambid::MAX_PARAMETERS);
static_assert(limits::max_matrix_values == ::ambid::MAX_MATRIX_VALUES);
static_assert(limits::max_frequencies == ::ambid::MAX_FREQUENCIES);
static_assert(limits::max_response_values == ::ambid::MAX_RESPONSE_VALUES);
static_assert(limits::max_peaks == ::ambid::MAX_PEAKS);
static_assert(static_cast<int>(AlertLevel::stale) == ::ambid::LEVEL_STALE);
static_assert(static_cast<int>(SourceKind::rig) == ::ambid::SOURCE_RIG);
static_assert(static_cast<int>(IsoZone::d) == ::ambid::ZONE_D);

// Same enumerators in the same order (asserted above).
template <class To, class From>
To enum_cast(From value) {
  return static_cast<To>(static_cast<std::underlying_type_t<From>>(value));
}

template <std::size_t N>
std::vector<fixed_string<N>> fixed(const std::vector<std::string>& in) {
  return {in.begin(), in.end()};
}

template <std::size_t N>
std::vector<std::string> strings(const std::vector<fixed_string<N>>& in) {
  std::vector<std::string> out;
  out.reserve(in.size());
  for (const auto& s : in) out.push_back(s.to_string());
  return out;
}

std::vector<::ambid::NamedValue> to_fast(const std::vector<NamedValue>& in) {
  std::vector<::ambid::NamedValue> out(in.size());
  for (std::size_t i = 0; i < in.size(); ++i) {
    out[i].name() = in[i].name;
    out[i].value(in[i].value);
  }
  return out;
}

std::vector<NamedValue> from_fast(const std::vector<::ambid::NamedValue>& in) {
  std::vector<NamedValue> out;
  out.reserve(in.size());
  for (const auto& v : in) out.push_back({v.name().to_string(), v.value()});
  return out;
}

std::vector<::ambid::Estimate> to_fast(const std::vector<Estimate>& in) {
  std::vector<::ambid::Estimate> out(in.size());
  for (std::size_t i = 0; i < in.size(); ++i) {
    out[i].name() = in[i].name;
    out[i].value(in[i].value);
    out[i].sigma(in[i].sigma);
  }
  return out;
}

std::vector<Estimate> from_fast(const std::vector<::ambid::Estimate>& in) {
  std::vector<Estimate> out;
  out.reserve(in.size());
  for (const auto& e : in) out.push_back({e.name().to_string(), e.value(), e.sigma()});
  return out;
}

void to_fast(const Matrix& in, ::ambid::Matrix& out) {
  out.rows(in.rows);
  out.cols(in.cols);
  out.values(in.values);
}

Matrix from_fast(const ::ambid::Matrix& in) { return {in.rows(), in.cols(), in.values()}; }

void to_fast(const StateSpace& in, ::ambid::StateSpace& out) {
  to_fast(in.a, out.a());
  to_fast(in.b, out.b());
  to_fast(in.c, out.c());
  to_fast(in.d, out.d());
}

StateSpace from_fast(const ::ambid::StateSpace& in) {
  return {from_fast(in.a()), from_fast(in.b()), from_fast(in.c()), from_fast(in.d())};
}

}  // namespace

void to_fast(const PlantSamples& in, ::ambid::PlantSamples& out) {
  out.plant_id() = in.plant_id;
  out.seq(in.seq);
  out.t0(in.t0);
  out.sample_time(in.sample_time);
  out.count(in.count);
  out.description_id() = in.description_id;
  out.y_names(fixed<::ambid::NAME_LENGTH>(in.y_names));
  out.u_names(fixed<::ambid::NAME_LENGTH>(in.u_names));
  out.r_names(fixed<::ambid::NAME_LENGTH>(in.r_names));
  out.y(in.y);
  out.u(in.u);
  out.r(in.r);
}

PlantSamples from_fast(const ::ambid::PlantSamples& in) {
  return {.plant_id = in.plant_id().to_string(),
          .seq = in.seq(),
          .t0 = in.t0(),
          .sample_time = in.sample_time(),
          .count = in.count(),
          .description_id = in.description_id().to_string(),
          .y_names = strings(in.y_names()),
          .u_names = strings(in.u_names()),
          .r_names = strings(in.r_names()),
          .y = in.y(),
          .u = in.u(),
          .r = in.r()};
}

void to_fast(const PlantDescription& in, ::ambid::PlantDescription& out) {
  out.plant_id() = in.plant_id;
  out.description_id() = in.description_id;
  out.model() = in.model;
  out.parameters(to_fast(in.parameters));
  out.sample_time(in.sample_time);
  out.y_names(fixed<::ambid::NAME_LENGTH>(in.y_names));
  out.u_names(fixed<::ambid::NAME_LENGTH>(in.u_names));
  out.r_names(fixed<::ambid::NAME_LENGTH>(in.r_names));
  out.operating_point(to_fast(in.operating_point));
  out.has_controller(in.has_controller);
  const ControllerDescription& c = in.controller;
  ::ambid::ControllerDescription& fc = out.controller();
  fc.kind() = c.kind;
  fc.sample_time(c.sample_time);
  fc.inputs(fixed<::ambid::NAME_LENGTH>(c.inputs));
  fc.outputs(fixed<::ambid::NAME_LENGTH>(c.outputs));
  to_fast(c.matrices, fc.matrices());
  to_fast(c.initial_state, fc.initial_state());
  to_fast(c.output_limits, fc.output_limits());
  to_fast(c.state_limits, fc.state_limits());
}

PlantDescription from_fast(const ::ambid::PlantDescription& in) {
  const ::ambid::ControllerDescription& c = in.controller();
  return {.plant_id = in.plant_id().to_string(),
          .description_id = in.description_id().to_string(),
          .model = in.model().to_string(),
          .parameters = from_fast(in.parameters()),
          .sample_time = in.sample_time(),
          .y_names = strings(in.y_names()),
          .u_names = strings(in.u_names()),
          .r_names = strings(in.r_names()),
          .operating_point = from_fast(in.operating_point()),
          .has_controller = in.has_controller(),
          .controller = {.kind = c.kind().to_string(),
                         .sample_time = c.sample_time(),
                         .inputs = strings(c.inputs()),
                         .outputs = strings(c.outputs()),
                         .matrices = from_fast(c.matrices()),
                         .initial_state = from_fast(c.initial_state()),
                         .output_limits = from_fast(c.output_limits()),
                         .state_limits = from_fast(c.state_limits())}};
}

void to_fast(const ExcitationCommand& in, ::ambid::ExcitationCommand& out) {
  out.plant_id() = in.plant_id;
  out.seq(in.seq);
  out.kind() = in.kind;
  out.channels(fixed<::ambid::NAME_LENGTH>(in.channels));
  out.amplitude(in.amplitude);
  out.duration(in.duration);
  out.seed(in.seed);
  out.settings(to_fast(in.settings));
  out.frequencies(in.frequencies);
}

ExcitationCommand from_fast(const ::ambid::ExcitationCommand& in) {
  return {.plant_id = in.plant_id().to_string(),
          .seq = in.seq(),
          .kind = in.kind().to_string(),
          .channels = strings(in.channels()),
          .amplitude = in.amplitude(),
          .duration = in.duration(),
          .seed = in.seed(),
          .settings = from_fast(in.settings()),
          .frequencies = in.frequencies()};
}

void to_fast(const PlantSourceCommand& in, ::ambid::PlantSourceCommand& out) {
  out.plant_id() = in.plant_id;
  out.seq(in.seq);
  out.kind(enum_cast<::ambid::SourceKind>(in.kind));
  out.target() = in.target;
}

PlantSourceCommand from_fast(const ::ambid::PlantSourceCommand& in) {
  return {.plant_id = in.plant_id().to_string(),
          .seq = in.seq(),
          .kind = enum_cast<SourceKind>(in.kind()),
          .target = in.target().to_string()};
}

void to_fast(const PlantSourceState& in, ::ambid::PlantSourceState& out) {
  out.plant_id() = in.plant_id;
  out.time(in.time);
  out.kind(enum_cast<::ambid::SourceKind>(in.kind));
  out.target() = in.target;
  out.command_seq(in.command_seq);
  out.command_accepted(in.command_accepted);
  out.message() = in.message;
}

PlantSourceState from_fast(const ::ambid::PlantSourceState& in) {
  return {.plant_id = in.plant_id().to_string(),
          .time = in.time(),
          .kind = enum_cast<SourceKind>(in.kind()),
          .target = in.target().to_string(),
          .command_seq = in.command_seq(),
          .command_accepted = in.command_accepted(),
          .message = in.message().to_string()};
}

void to_fast(const IdentifiedModel& in, ::ambid::IdentifiedModel& out) {
  out.plant_id() = in.plant_id;
  out.seq(in.seq);
  out.time(in.time);
  out.window(in.window);
  out.plant_model() = in.plant_model;
  out.method() = in.method;
  out.sample_time(in.sample_time);
  to_fast(in.discrete, out.discrete());
  to_fast(in.continuous, out.continuous());
  out.parameters(to_fast(in.parameters));
  out.physical(to_fast(in.physical));
  out.nrmse(to_fast(in.nrmse));
}

IdentifiedModel from_fast(const ::ambid::IdentifiedModel& in) {
  return {.plant_id = in.plant_id().to_string(),
          .seq = in.seq(),
          .time = in.time(),
          .window = in.window(),
          .plant_model = in.plant_model().to_string(),
          .method = in.method().to_string(),
          .sample_time = in.sample_time(),
          .discrete = from_fast(in.discrete()),
          .continuous = from_fast(in.continuous()),
          .parameters = from_fast(in.parameters()),
          .physical = from_fast(in.physical()),
          .nrmse = from_fast(in.nrmse())};
}

void to_fast(const FrequencyResponse& in, ::ambid::FrequencyResponse& out) {
  out.plant_id() = in.plant_id;
  out.kind() = in.kind;
  out.seq(in.seq);
  out.time(in.time);
  out.outputs(fixed<::ambid::NAME_LENGTH>(in.outputs));
  out.inputs(fixed<::ambid::NAME_LENGTH>(in.inputs));
  out.frequencies(in.frequencies);
  out.re(in.re);
  out.im(in.im);
  std::vector<::ambid::SensitivityPeak> peaks(in.peaks.size());
  for (std::size_t i = 0; i < in.peaks.size(); ++i) {
    peaks[i].output() = in.peaks[i].output;
    peaks[i].frequency(in.peaks[i].frequency);
    peaks[i].magnitude(in.peaks[i].magnitude);
    peaks[i].zone(enum_cast<::ambid::IsoZone>(in.peaks[i].zone));
  }
  out.peaks(std::move(peaks));
  out.zone(enum_cast<::ambid::IsoZone>(in.zone));
}

FrequencyResponse from_fast(const ::ambid::FrequencyResponse& in) {
  std::vector<SensitivityPeak> peaks;
  peaks.reserve(in.peaks().size());
  for (const auto& p : in.peaks()) {
    peaks.push_back({p.output().to_string(), p.frequency(), p.magnitude(), enum_cast<IsoZone>(p.zone())});
  }
  return {.plant_id = in.plant_id().to_string(),
          .kind = in.kind().to_string(),
          .seq = in.seq(),
          .time = in.time(),
          .outputs = strings(in.outputs()),
          .inputs = strings(in.inputs()),
          .frequencies = in.frequencies(),
          .re = in.re(),
          .im = in.im(),
          .peaks = std::move(peaks),
          .zone = enum_cast<IsoZone>(in.zone())};
}

void to_fast(const Alert& in, ::ambid::Alert& out) {
  out.plant_id() = in.plant_id;
  out.fault() = in.fault;
  out.channel(in.channel);
  out.time(in.time);
  out.level(enum_cast<::ambid::AlertLevel>(in.level));
  out.parameter() = in.parameter;
  out.value(in.value);
  out.baseline(in.baseline);
  out.message() = in.message;
}

Alert from_fast(const ::ambid::Alert& in) {
  return {.plant_id = in.plant_id().to_string(),
          .fault = in.fault().to_string(),
          .channel = in.channel(),
          .time = in.time(),
          .level = enum_cast<AlertLevel>(in.level()),
          .parameter = in.parameter().to_string(),
          .value = in.value(),
          .baseline = in.baseline(),
          .message = in.message().to_string()};
}

void to_fast(const Health& in, ::ambid::Health& out) {
  out.node() = in.node;
  out.role() = in.role;
  out.time(in.time);
  out.level(enum_cast<::ambid::AlertLevel>(in.level));
  out.message() = in.message;
  out.received(in.received);
  out.published(in.published);
  out.errors(in.errors);
}

Health from_fast(const ::ambid::Health& in) {
  return {.node = in.node().to_string(),
          .role = in.role().to_string(),
          .time = in.time(),
          .level = enum_cast<AlertLevel>(in.level()),
          .message = in.message().to_string(),
          .received = in.received(),
          .published = in.published(),
          .errors = in.errors()};
}

}  // namespace ambid::bus::fastdds
