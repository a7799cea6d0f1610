#include "services/bus/validate.hpp"

#include <string>
#include <string_view>
#include <vector>

namespace ambid::bus {
namespace {

std::string preview(const std::string& value) {
  constexpr std::size_t shown = 40;
  std::string text = value.size() <= shown ? value : value.substr(0, shown) + "...";
  for (char& c : text) {
    if (c == '\0') c = '?';
  }
  return "\"" + text + "\"";
}

// Collects nothing: the first violation throws, naming "Type.field[index]".
class Checker {
 public:
  explicit Checker(std::string_view type) : type_(type) {}

  void text(std::string_view field, const std::string& value, std::size_t bound) const {
    if (value.size() > bound) {
      fail(field, "is " + std::to_string(value.size()) + " characters, more than its bound of " +
                      std::to_string(bound) + " (" + preview(value) + ")");
    }
    if (value.find('\0') != std::string::npos) {
      fail(field, "holds a NUL character (" + preview(value) + ")");
    }
  }

  void texts(std::string_view field, const std::vector<std::string>& values, std::size_t max, std::size_t bound) const {
    size(field, values.size(), max);
    for (std::size_t i = 0; i < values.size(); ++i) {
      text(indexed(field, i), values[i], bound);
    }
  }

  void size(std::string_view field, std::size_t n, std::size_t max) const {
    if (n > max) {
      fail(field, "has " + std::to_string(n) + " entries, more than its bound of " + std::to_string(max));
    }
  }

  void length(std::string_view field, std::size_t n, std::size_t expected, std::string_view because) const {
    if (n != expected) {
      fail(field, "has " + std::to_string(n) + " entries, expected " + std::string(because) + " = " +
                      std::to_string(expected));
    }
  }

  template <class Enum>
  void enumeration(std::string_view field, Enum value, Enum last) const {
    if (static_cast<unsigned>(value) > static_cast<unsigned>(last)) {
      fail(field, "has the out-of-range value " + std::to_string(static_cast<unsigned>(value)));
    }
  }

  void matrix(std::string_view field, const Matrix& m) const {
    const std::string f(field);
    size(f + ".values", m.values.size(), limits::max_matrix_values);
    length(f + ".values", m.values.size(), std::size_t{m.rows} * m.cols,
           "rows x cols = " + std::to_string(m.rows) + " x " + std::to_string(m.cols));
  }

  void state_space(std::string_view field, const StateSpace& s) const {
    const std::string f(field);
    matrix(f + ".a", s.a);
    matrix(f + ".b", s.b);
    matrix(f + ".c", s.c);
    matrix(f + ".d", s.d);
  }

  // NamedValue and Estimate lists: bounded, and every name bounded.
  template <class Named>
  void named(std::string_view field, const std::vector<Named>& values, std::size_t max) const {
    size(field, values.size(), max);
    for (std::size_t i = 0; i < values.size(); ++i) {
      text(indexed(field, i) + ".name", values[i].name, limits::name_length);
    }
  }

  static std::string indexed(std::string_view field, std::size_t i) {
    return std::string(field) + "[" + std::to_string(i) + "]";
  }

 private:
  [[noreturn]] void fail(std::string_view field, const std::string& what) const {
    throw InvalidMessage(std::string(type_) + "." + std::string(field) + " " + what);
  }

  std::string_view type_;
};

void signal_group(const Checker& check, std::string_view group, const PlantSamples& m,
                  const std::vector<std::string>& names, const std::vector<double>& values) {
  const std::string names_field = std::string(group) + "_names";
  check.texts(names_field, names, limits::max_channels, limits::name_length);
  check.size(group, values.size(), limits::max_batch_values);
  check.length(group, values.size(), std::size_t{m.count} * names.size(),
               "count x " + names_field + " = " + std::to_string(m.count) + " x " + std::to_string(names.size()));
}

}  // namespace

void validate(const PlantSamples& m) {
  const Checker check("PlantSamples");
  check.text("plant_id", m.plant_id, limits::id_length);
  check.text("description_id", m.description_id, limits::id_length);
  signal_group(check, "y", m, m.y_names, m.y);
  signal_group(check, "u", m, m.u_names, m.u);
  signal_group(check, "r", m, m.r_names, m.r);
}

void validate(const PlantDescription& m) {
  const Checker check("PlantDescription");
  check.text("plant_id", m.plant_id, limits::id_length);
  check.text("description_id", m.description_id, limits::id_length);
  check.text("model", m.model, limits::name_length);
  check.named("parameters", m.parameters, limits::max_parameters);
  check.texts("y_names", m.y_names, limits::max_channels, limits::name_length);
  check.texts("u_names", m.u_names, limits::max_channels, limits::name_length);
  check.texts("r_names", m.r_names, limits::max_channels, limits::name_length);
  check.named("operating_point", m.operating_point, limits::max_parameters);
  const ControllerDescription& c = m.controller;
  check.text("controller.kind", c.kind, limits::name_length);
  check.texts("controller.inputs", c.inputs, limits::max_channels, limits::name_length);
  check.texts("controller.outputs", c.outputs, limits::max_channels, limits::name_length);
  check.state_space("controller.matrices", c.matrices);
  check.matrix("controller.initial_state", c.initial_state);
  check.matrix("controller.output_limits", c.output_limits);
  check.matrix("controller.state_limits", c.state_limits);
}

void validate(const ExcitationCommand& m) {
  const Checker check("ExcitationCommand");
  check.text("plant_id", m.plant_id, limits::id_length);
  check.text("kind", m.kind, limits::name_length);
  check.texts("channels", m.channels, limits::max_channels, limits::name_length);
  check.named("settings", m.settings, limits::max_parameters);
  check.size("frequencies", m.frequencies.size(), limits::max_frequencies);
}

void validate(const PlantSourceCommand& m) {
  const Checker check("PlantSourceCommand");
  check.text("plant_id", m.plant_id, limits::id_length);
  check.enumeration("kind", m.kind, SourceKind::rig);
  check.text("target", m.target, limits::text_length);
}

void validate(const PlantSourceState& m) {
  const Checker check("PlantSourceState");
  check.text("plant_id", m.plant_id, limits::id_length);
  check.enumeration("kind", m.kind, SourceKind::rig);
  check.text("target", m.target, limits::text_length);
  check.text("message", m.message, limits::text_length);
}

void validate(const IdentifiedModel& m) {
  const Checker check("IdentifiedModel");
  check.text("plant_id", m.plant_id, limits::id_length);
  check.text("plant_model", m.plant_model, limits::name_length);
  check.text("method", m.method, limits::name_length);
  check.state_space("discrete", m.discrete);
  check.state_space("continuous", m.continuous);
  check.named("parameters", m.parameters, limits::max_parameters);
  check.named("physical", m.physical, limits::max_parameters);
  check.named("nrmse", m.nrmse, limits::max_channels);
}

void validate(const FrequencyResponse& m) {
  const Checker check("FrequencyResponse");
  check.text("plant_id", m.plant_id, limits::id_length);
  check.text("kind", m.kind, limits::name_length);
  check.texts("outputs", m.outputs, limits::max_channels, limits::name_length);
  check.texts("inputs", m.inputs, limits::max_channels, limits::name_length);
  check.size("frequencies", m.frequencies.size(), limits::max_frequencies);
  const std::size_t expected = m.outputs.size() * m.inputs.size() * m.frequencies.size();
  const std::string because = "outputs x inputs x frequencies = " + std::to_string(m.outputs.size()) + " x " +
                              std::to_string(m.inputs.size()) + " x " + std::to_string(m.frequencies.size());
  check.size("re", m.re.size(), limits::max_response_values);
  check.length("re", m.re.size(), expected, because);
  check.size("im", m.im.size(), limits::max_response_values);
  check.length("im", m.im.size(), expected, because);
  check.size("peaks", m.peaks.size(), limits::max_peaks);
  for (std::size_t i = 0; i < m.peaks.size(); ++i) {
    const std::string peak = Checker::indexed("peaks", i);
    check.text(peak + ".output", m.peaks[i].output, limits::name_length);
    check.enumeration(peak + ".zone", m.peaks[i].zone, IsoZone::d);
  }
  check.enumeration("zone", m.zone, IsoZone::d);
}

void validate(const Alert& m) {
  const Checker check("Alert");
  check.text("plant_id", m.plant_id, limits::id_length);
  check.text("fault", m.fault, limits::name_length);
  check.enumeration("level", m.level, AlertLevel::stale);
  check.text("parameter", m.parameter, limits::name_length);
  check.text("message", m.message, limits::text_length);
}

void validate(const Health& m) {
  const Checker check("Health");
  check.text("node", m.node, limits::id_length);
  check.text("role", m.role, limits::name_length);
  check.enumeration("level", m.level, AlertLevel::stale);
  check.text("message", m.message, limits::text_length);
}

}  // namespace ambid::bus
