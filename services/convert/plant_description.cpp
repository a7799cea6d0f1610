#include "services/convert/plant_description.hpp"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>

#include <nlohmann/json.hpp>

#include "core/error.hpp"

namespace ambid::convert {
namespace {

constexpr double inf = std::numeric_limits<double>::infinity();

bus::Matrix to_matrix(const Eigen::MatrixXd& m) {
  bus::Matrix out{std::uint32_t(m.rows()), std::uint32_t(m.cols()), {}};
  out.values.reserve(std::size_t(m.size()));
  for (Eigen::Index i = 0; i < m.rows(); ++i)
    for (Eigen::Index j = 0; j < m.cols(); ++j) out.values.push_back(m(i, j));
  return out;
}

// A matrix as received (a writer of another program may not have validated it).
void check_dimensions(const bus::Matrix& m, const std::string& field) {
  if (m.values.size() != std::size_t(m.rows) * m.cols)
    throw Error("plant description: " + field + " holds " + std::to_string(m.values.size()) + " values, not " +
                std::to_string(m.rows) + " x " + std::to_string(m.cols));
}

Eigen::MatrixXd from_matrix(const bus::Matrix& m) {
  Eigen::MatrixXd out(m.rows, m.cols);
  for (Eigen::Index i = 0; i < out.rows(); ++i)
    for (Eigen::Index j = 0; j < out.cols(); ++j) out(i, j) = m.values.at(std::size_t(i * out.cols() + j));
  return out;
}

std::vector<bus::NamedValue> named(const std::map<std::string, double>& values) {
  std::vector<bus::NamedValue> out;
  for (const auto& [name, value] : values) out.push_back({name, value});
  return out;
}

std::map<std::string, double> unnamed(const std::vector<bus::NamedValue>& values, const std::string& field) {
  std::map<std::string, double> out;
  for (const auto& [name, value] : values)
    if (!out.emplace(name, value).second) throw Error("plant description: " + field + " names '" + name + "' twice");
  return out;
}

// The sidecar's `[[lo, hi] | null, ...]` (null: no limit) as an n x 2 matrix with infinities.
// Clamps as a rows x 2 matrix of [lo, hi]; an infinite bound is no bound on that side.
bus::Matrix limits_matrix(const std::vector<Limit>& limits) {
  bus::Matrix out{std::uint32_t(limits.size()), 2, {}};
  for (const Limit& l : limits) {
    out.values.push_back(l.lo);
    out.values.push_back(l.hi);
  }
  return out;
}

std::vector<Limit> limits_of(const bus::Matrix& m, const std::string& field) {
  if (m.rows > 0 && m.cols != 2)
    throw Error("plant description: controller." + field + " has " + std::to_string(m.cols) +
                " columns, expected 2 ([lo, hi])");
  std::vector<Limit> out;
  for (std::size_t i = 0; i < m.rows; ++i) out.push_back({m.values[2 * i], m.values[2 * i + 1]});
  return out;
}

// Canonical serialisation: every value tagged and self-delimiting, so no two contents share one.
class Canonical {
 public:
  void text(const std::string& s) { out_ += "s" + std::to_string(s.size()) + ":" + s; }
  void number(double v) {
    char buffer[40];
    std::snprintf(buffer, sizeof buffer, "d%a;", v);
    out_ += buffer;
  }
  void texts(const std::vector<std::string>& v) {
    out_ += "l" + std::to_string(v.size()) + ":";
    for (const auto& s : v) text(s);
  }
  void named(const std::vector<bus::NamedValue>& v) {
    out_ += "n" + std::to_string(v.size()) + ":";
    for (const auto& [name, value] : v) {
      text(name);
      number(value);
    }
  }
  void matrix(const bus::Matrix& m) {
    out_ += "m" + std::to_string(m.rows) + "x" + std::to_string(m.cols) + ":";
    for (double v : m.values) number(v);
  }
  const std::string& str() const { return out_; }

 private:
  std::string out_;
};

std::uint64_t fnv1a(const std::string& s) {
  std::uint64_t h = 14695981039346656037ull;
  for (unsigned char c : s) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return h;
}

}  // namespace

std::string description_id(const bus::PlantDescription& d) {
  Canonical c;
  c.text(d.model);
  c.named(d.parameters);
  c.number(d.sample_time);
  c.texts(d.y_names);
  c.texts(d.u_names);
  c.texts(d.r_names);
  c.named(d.operating_point);
  c.text(d.has_controller ? "controller" : "none");
  const bus::ControllerDescription& k = d.controller;
  c.text(k.kind);
  c.number(k.sample_time);
  c.texts(k.inputs);
  c.texts(k.outputs);
  for (const bus::Matrix* m : {&k.matrices.a, &k.matrices.b, &k.matrices.c, &k.matrices.d, &k.initial_state,
                               &k.output_limits, &k.state_limits})
    c.matrix(*m);
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(fnv1a(c.str())));
  return hex;
}

bus::PlantDescription describe(const Experiment& header, const std::string& plant_id) {
  header.validate_metadata();
  bus::PlantDescription d;
  d.plant_id = plant_id;
  d.model = header.plant.model;
  d.parameters = named(header.plant.parameters);
  d.sample_time = header.sample_time;
  d.y_names = header.y_names;
  d.u_names = header.u_names;
  d.r_names = header.r_names;
  d.operating_point = named(header.operating_point);
  d.controller.output_limits = d.controller.state_limits = {0, 2, {}};
  if (const auto& k = header.controller) {
    d.has_controller = true;
    d.controller.kind = k->kind;
    d.controller.sample_time = k->sample_time;
    d.controller.inputs = k->inputs;
    d.controller.outputs = k->outputs;
    d.controller.matrices = {to_matrix(k->A), to_matrix(k->B), to_matrix(k->C), to_matrix(k->D)};
    if (k->initial_state.size() > 0) d.controller.initial_state = to_matrix(k->initial_state);
    d.controller.output_limits = limits_matrix(k->output_limits);
    d.controller.state_limits = limits_matrix(k->state_limits);
  }
  d.description_id = description_id(d);
  return d;
}

Experiment experiment_header(const bus::PlantDescription& d) {
  if (const std::string id = description_id(d); id != d.description_id)
    throw Error("plant description of '" + d.plant_id + "': id '" + d.description_id +
                "' does not match its content (hash " + id + ")");
  const bus::ControllerDescription& k = d.controller;
  for (const auto& [field, m] : {std::pair{"controller.A", &k.matrices.a},
                                 {"controller.B", &k.matrices.b},
                                 {"controller.C", &k.matrices.c},
                                 {"controller.D", &k.matrices.d},
                                 {"controller.initial_state", &k.initial_state},
                                 {"controller.output_limits", &k.output_limits},
                                 {"controller.state_limits", &k.state_limits}})
    check_dimensions(*m, field);
  Experiment e;
  e.name = d.plant_id + " description " + d.description_id;
  e.sample_time = d.sample_time;
  e.plant = {d.model, unnamed(d.parameters, "parameters")};
  e.y_names = d.y_names;
  e.u_names = d.u_names;
  e.r_names = d.r_names;
  e.operating_point = unnamed(d.operating_point, "operating_point");
  if (d.has_controller) {
    StateSpaceController c;
    c.kind = k.kind;
    c.sample_time = k.sample_time;
    c.inputs = k.inputs;
    c.outputs = k.outputs;
    c.A = from_matrix(k.matrices.a);
    c.B = from_matrix(k.matrices.b);
    c.C = from_matrix(k.matrices.c);
    c.D = from_matrix(k.matrices.d);
    if (k.initial_state.values.size() > 0) c.initial_state = from_matrix(k.initial_state).reshaped();
    c.output_limits = limits_of(k.output_limits, "output_limits");
    c.state_limits = limits_of(k.state_limits, "state_limits");
    e.controller = std::move(c);
  }
  try {
    e.validate_metadata();
  } catch (const Error& error) {
    throw Error("plant description of '" + d.plant_id + "': " + error.what());
  }
  return e;
}

std::string controller_summary(const bus::PlantDescription& d) {
  if (!d.has_controller) return "none";
  return d.controller.kind + " " + std::to_string(d.controller.matrices.a.rows) + " states";
}

}  // namespace ambid::convert
