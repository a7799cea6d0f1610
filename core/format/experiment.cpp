#include "core/experiment.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <string>
#include <tuple>

#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "core/format/experiment_sidecar.hpp"
#include "core/format/experiment_text.hpp"

namespace ambid {
namespace {

std::string size_text(Eigen::Index rows, Eigen::Index cols) {
  return std::to_string(rows) + "x" + std::to_string(cols);
}

std::string join(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out.empty() ? "(none)" : out;
}

bool contains(const std::vector<std::string>& names, const std::string& name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

void require_positive_finite(double value, const std::string& key) {
  if (!(value > 0.0) || !std::isfinite(value))
    throw Error(key + " must be a positive finite number of seconds, got " + number_text(value));
}

void require_shape(const Eigen::MatrixXd& m, Eigen::Index rows, Eigen::Index cols, const std::string& key,
                   const std::string& meaning) {
  if (m.rows() != rows || m.cols() != cols)
    throw Error(key + " must be " + size_text(rows, cols) + " (" + meaning + "), got " + dims(m));
}

void require_finite(const Eigen::MatrixXd& m, const std::string& key) {
  for (Eigen::Index i = 0; i < m.rows(); ++i)
    for (Eigen::Index j = 0; j < m.cols(); ++j)
      if (!std::isfinite(m(i, j)))
        throw Error(key + "[" + std::to_string(i) + "][" + std::to_string(j) + "] must be finite, got " +
                    number_text(m(i, j)));
}

void require_finite(const Eigen::VectorXd& v, const std::string& key) {
  for (Eigen::Index i = 0; i < v.size(); ++i)
    if (!std::isfinite(v(i))) throw Error(key + "[" + std::to_string(i) + "] must be finite, got " + number_text(v(i)));
}

void require_limits(const std::vector<Limit>& limits, Eigen::Index count, const std::string& key,
                    const std::string& meaning) {
  if (limits.empty()) return;
  if (static_cast<Eigen::Index>(limits.size()) != count)
    throw Error(key + " must have " + std::to_string(count) + " entries (" + meaning + "), got " +
                std::to_string(limits.size()));
  for (std::size_t i = 0; i < limits.size(); ++i)
    if (!(limits[i].lo < limits[i].hi))
      throw Error(key + "[" + std::to_string(i) + "] must be [lo, hi] with lo < hi, got [" + number_text(limits[i].lo) +
                  ", " + number_text(limits[i].hi) + "]");
}

void require_distinct(const std::vector<std::string>& names, const std::string& key) {
  std::set<std::string> seen;
  for (const auto& n : names)
    if (!seen.insert(n).second) throw Error(key + " names '" + n + "' twice");
}

// Names become CSV header cells, so they must survive the trip through an unquoted header.
void require_signal_name(const std::string& name, const std::string& key) {
  if (name.empty()) throw Error(key + " has an empty signal name");
  if (name == "t") throw Error(key + " may not name a signal 't': that is the time column");
  if (name.find_first_of(",\"\r\n") != std::string::npos)
    throw Error(key + " signal name " + quote_excerpt(name) +
                " contains a comma, quote or line break, which a CSV header cannot hold");
  if (name.front() == ' ' || name.front() == '\t' || name.back() == ' ' || name.back() == '\t')
    throw Error(key + " signal name " + quote_excerpt(name) + " has leading or trailing whitespace");
}

void validate_extra(const nlohmann::json& extra, bool has_controller) {
  if (extra.is_null()) return;
  if (!extra.is_object()) throw Error("extra must be a JSON object, got " + std::string(extra.type_name()));
  const auto& top = defined_sidecar_keys().at("");
  for (const auto& [key, value] : extra.items()) {
    // "" is the top level's entry in defined_sidecar_keys(), not a nested object.
    const auto nested = key.empty() ? defined_sidecar_keys().end() : defined_sidecar_keys().find(key);
    if (nested == defined_sidecar_keys().end()) {
      if (top.count(key)) throw Error("extra holds '" + key + "', a key the format defines");
      continue;
    }
    if (!value.is_object())
      throw Error("extra." + key + " must be an object of unknown " + key + " keys, got " + value.type_name());
    if (key == "controller" && !has_controller)
      throw Error("extra.controller holds keys but the experiment has no controller");
    for (const auto& item : value.items())
      if (nested->second.count(item.key()))
        throw Error("extra." + key + " holds '" + item.key() + "', a key the format defines");
  }
}

}  // namespace

std::optional<Eigen::Index> find_sampling_gap(const Eigen::VectorXd& t, double sample_time) {
  for (Eigen::Index k = 1; k < t.size(); ++k)
    if (!(std::abs(t(k) - t(k - 1) - sample_time) <= kSamplingTolerance * sample_time)) return k;
  return std::nullopt;
}

void StateSpaceController::validate(const std::vector<std::string>& plant_inputs) const {
  if (kind != "state_space") throw Error("controller.kind must be 'state_space', got " + quote_excerpt(kind));
  require_positive_finite(sample_time, "controller.sample_time");
  if (inputs.empty()) throw Error("controller.inputs must name at least one signal");
  if (outputs.empty()) throw Error("controller.outputs must name at least one u signal");
  require_distinct(inputs, "controller.inputs");
  require_distinct(outputs, "controller.outputs");
  for (const auto& out : outputs)
    if (!contains(plant_inputs, out))
      throw Error("controller.outputs names '" + out + "', which is not a u signal (signals.u: " + join(plant_inputs) +
                  ")");
  const Eigen::Index n = A.rows();
  const auto p = static_cast<Eigen::Index>(inputs.size());
  const auto q = static_cast<Eigen::Index>(outputs.size());
  require_shape(A, n, n, "controller.A", "states x states");
  require_shape(B, n, p, "controller.B", "states x inputs");
  require_shape(C, q, n, "controller.C", "outputs x states");
  require_shape(D, q, p, "controller.D", "outputs x inputs");
  if (initial_state.size() != 0 && initial_state.size() != n)
    throw Error("controller.initial_state must have " + std::to_string(n) + " entries (states), got " +
                std::to_string(initial_state.size()));
  require_finite(A, "controller.A");
  require_finite(B, "controller.B");
  require_finite(C, "controller.C");
  require_finite(D, "controller.D");
  require_finite(initial_state, "controller.initial_state");
  require_limits(output_limits, q, "controller.output_limits", "one per output");
  require_limits(state_limits, n, "controller.state_limits", "one per state");
  for (Eigen::Index j = 0; j < p; ++j) {
    const std::string& in = inputs[static_cast<std::size_t>(j)];
    if (!contains(plant_inputs, in)) continue;
    for (Eigen::Index i = 0; i < q; ++i)
      if (D(i, j) != 0.0)
        throw Error("controller.D column " + std::to_string(j) + " (input '" + in +
                    "') must be zero: feeding the plant input '" + in + "' through D is an algebraic loop; got D[" +
                    std::to_string(i) + "][" + std::to_string(j) + "] = " + number_text(D(i, j)));
  }
}

std::vector<std::string> Experiment::signal_names() const {
  std::vector<std::string> names = y_names;
  names.insert(names.end(), u_names.begin(), u_names.end());
  names.insert(names.end(), r_names.begin(), r_names.end());
  return names;
}

double Experiment::operating_value(const std::string& signal) const {
  const auto it = operating_point.find(signal);
  return it == operating_point.end() ? 0.0 : it->second;
}

Eigen::VectorXd Experiment::operating_values(const std::vector<std::string>& signals) const {
  Eigen::VectorXd values(static_cast<Eigen::Index>(signals.size()));
  for (std::size_t i = 0; i < signals.size(); ++i) values(static_cast<Eigen::Index>(i)) = operating_value(signals[i]);
  return values;
}

Eigen::MatrixXd Experiment::y_deviation() const { return y.rowwise() - operating_values(y_names).transpose(); }

Eigen::MatrixXd Experiment::u_deviation() const { return u.rowwise() - operating_values(u_names).transpose(); }

Eigen::MatrixXd Experiment::r_deviation() const { return r.rowwise() - operating_values(r_names).transpose(); }

Eigen::VectorXd Experiment::signal(const std::string& wanted) const {
  const std::pair<const std::vector<std::string>*, const Eigen::MatrixXd*> groups[] = {
      {&y_names, &y}, {&u_names, &u}, {&r_names, &r}};
  for (const auto& [names, values] : groups) {
    const auto it = std::find(names->begin(), names->end(), wanted);
    if (it != names->end()) return values->col(it - names->begin());
  }
  throw Error("experiment '" + name + "' has no signal '" + wanted + "'; its signals are " + join(signal_names()));
}

void Experiment::validate_metadata() const {
  require_positive_finite(sample_time, "sample_time");
  if (plant.model.empty()) throw Error("plant.model must name a plant model, got an empty string");
  for (const auto& [key, value] : plant.parameters)
    if (!std::isfinite(value)) throw Error("plant.parameters." + key + " must be finite, got " + number_text(value));

  if (y_names.empty()) throw Error("signals.y must name at least one output signal");
  if (u_names.empty()) throw Error("signals.u must name at least one plant input signal");
  // u[k] = uf[k] + r[k]: the excitation is a vector over the plant inputs.
  if (!r_names.empty() && r_names.size() != u_names.size())
    throw Error("signals.r must name one excitation per u signal (" + std::to_string(u_names.size()) + "), got " +
                std::to_string(r_names.size()));
  const std::pair<const std::vector<std::string>*, const char*> groups[] = {
      {&y_names, "signals.y"}, {&u_names, "signals.u"}, {&r_names, "signals.r"}};
  std::map<std::string, std::string> group_of;
  for (const auto& [names, key] : groups)
    for (const auto& n : *names) {
      require_signal_name(n, key);
      const auto [it, fresh] = group_of.emplace(n, key);
      if (!fresh) throw Error(std::string(key) + " names '" + n + "', already named in " + it->second);
    }

  for (const auto& [key, value] : operating_point)
    if (!std::isfinite(value)) throw Error("operating_point." + key + " must be finite, got " + number_text(value));
  for (const auto* names : {&y_names, &u_names})
    for (const auto& n : *names)
      if (!operating_point.count(n))
        throw Error("operating_point." + n +
                    " is missing: every y and u signal needs its operating value (only r "
                    "signals default to 0)");

  if (controller) {
    controller->validate(u_names);
    for (const auto& in : controller->inputs)
      if (!group_of.count(in))
        throw Error("controller.inputs names '" + in +
                    "', which is no y, u or r signal (signals: " + join(signal_names()) + ")");
    if (!(std::abs(controller->sample_time - sample_time) <= 1e-9 * sample_time))
      throw Error("controller.sample_time " + number_text(controller->sample_time) + " must equal sample_time " +
                  number_text(sample_time) + " (within 1e-9 relative)");
  }
  validate_extra(extra.json(), controller.has_value());
}

void Experiment::validate() const {
  validate_metadata();
  const Eigen::Index n = samples();
  if (n < 2) throw Error("an experiment needs at least 2 samples, got " + std::to_string(n));
  const std::tuple<const Eigen::MatrixXd*, const std::vector<std::string>*, const char*> groups[] = {
      {&y, &y_names, "y"}, {&u, &u_names, "u"}, {&r, &r_names, "r"}};
  for (const auto& [values, names, key] : groups) {
    const auto cols = static_cast<Eigen::Index>(names->size());
    if (cols == 0 && values->cols() == 0) continue;  // no excitation: r may be left empty
    require_shape(*values, n, cols, key, "samples x signals");
    for (Eigen::Index j = 0; j < cols; ++j)
      for (Eigen::Index k = 0; k < n; ++k)
        if (!std::isfinite((*values)(k, j)))
          throw Error("sample " + std::to_string(k) + " of signal '" + (*names)[static_cast<std::size_t>(j)] +
                      "' must be finite, got " + number_text((*values)(k, j)));
  }
  for (Eigen::Index k = 0; k < n; ++k)
    if (!std::isfinite(t(k))) throw Error("t[" + std::to_string(k) + "] must be finite, got " + number_text(t(k)));
  for (Eigen::Index k = 1; k < n; ++k)
    if (!(t(k) > t(k - 1)))
      throw Error("t must be strictly increasing, but t[" + std::to_string(k) + "] = " + number_text(t(k)) +
                  " follows t[" + std::to_string(k - 1) + "] = " + number_text(t(k - 1)));
  if (const auto k = find_sampling_gap(t, sample_time))
    throw Error("sampling is not uniform: t[" + std::to_string(*k) + "] - t[" + std::to_string(*k - 1) +
                "] = " + number_text(t(*k) - t(*k - 1)) + " s, expected sample_time " + number_text(sample_time) +
                " s within 1 %");
}

}  // namespace ambid
