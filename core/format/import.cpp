// `ambid import`: a foreign record plus a mapping -> a contract experiment.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>

#include <nlohmann/json.hpp>

#include "core/controller_replay.hpp"
#include "core/error.hpp"
#include "core/experiment_import.hpp"
#include "core/format/experiment_text.hpp"
#include "core/format/recorded_columns.hpp"
#include "core/format/resample.hpp"

namespace ambid {
namespace {

constexpr double kDefaultMaxGapSteps = 10.0;  // resampling refuses longer steps (in sample times)

bool is_mat_file(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  char head[6] = {};
  in.read(head, sizeof head);
  return in && std::string_view(head, sizeof head) == "MATLAB";  // the text header of MAT v5 and v7.3
}

std::string describe(const SignalSource& s, const std::string& kind) {
  std::string text = s.name + " <- " + (kind == "CSV" ? "column '" : "variable '") + s.source + "'";
  if (!s.unit.empty()) text += " in " + s.unit + " (x" + number_text(unit_factor(s.unit)) + ")";
  if (s.scale != 1.0) text += " scaled by " + number_text(s.scale);
  return text;
}

std::vector<std::string> names_of(const std::vector<SignalSource>& sources) {
  std::vector<std::string> names;
  for (const auto& s : sources) names.push_back(s.name);
  return names;
}

std::string join(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out.empty() ? "(none)" : out;
}

// The mapping of every name in `wanted` (a template's signals), in that order.
std::vector<SignalSource> in_order(const std::vector<SignalSource>& mapped, const std::vector<std::string>& wanted,
                                   const std::string& group) {
  std::set<std::string> mapped_names;
  for (const auto& s : mapped)
    if (!mapped_names.insert(s.name).second) throw Error("the mapping names signal '" + s.name + "' twice");
  if (mapped_names != std::set<std::string>(wanted.begin(), wanted.end()))
    throw Error("the template's signals." + group + " are " + join(wanted) + " but the mapping gives " +
                join(names_of(mapped)) + "; map each of them once");
  std::vector<SignalSource> ordered;
  for (const auto& name : wanted)
    ordered.push_back(
        *std::find_if(mapped.begin(), mapped.end(), [&](const SignalSource& s) { return s.name == name; }));
  return ordered;
}

// The median step of t to 9 significant digits: differences of time stamps carry round-off
// (0.03 - 0.01 = 0.019999999999999574) that would otherwise become the sample time.
double median_step(const Eigen::VectorXd& t) {
  std::vector<double> steps(std::size_t(t.size() - 1));
  for (Eigen::Index k = 1; k < t.size(); ++k) steps[std::size_t(k - 1)] = t(k) - t(k - 1);
  std::nth_element(steps.begin(), steps.begin() + std::ptrdiff_t(steps.size() / 2), steps.end());
  const double median = steps[steps.size() / 2];
  if (!(median > 0.0)) return median;
  const double unit = std::pow(10.0, std::floor(std::log10(median)) - 8);
  return std::round(median / unit) * unit;
}

// Checks that t increases, and when its steps are not uniform within 1 % of T, resamples t and
// values onto the uniform grid (or refuses, naming the step).
void uniform_time(Eigen::VectorXd& t, Eigen::MatrixXd& values, double T, const ImportOptions& options,
                  ImportResult& result) {
  for (Eigen::Index k = 1; k < t.size(); ++k)
    if (!(t(k) > t(k - 1)))
      throw Error("time is not strictly increasing: row " + std::to_string(k + 1) + " has t = " + number_text(t(k)) +
                  " s after t = " + number_text(t(k - 1)) + " s on row " + std::to_string(k));
  const auto gap = find_sampling_gap(t, T);
  if (!gap) return;
  const std::string where = "t steps by " + number_text(t(*gap) - t(*gap - 1)) +
                            " s from t = " + number_text(t(*gap - 1)) + " s (row " + std::to_string(*gap) + ")";
  if (!options.resample)
    throw Error("sampling is not uniform: " + where + ", expected the sample time " + number_text(T) +
                " s within 1 %; --resample interpolates onto a uniform grid");
  const double max_gap = options.max_gap > 0.0 ? options.max_gap : kDefaultMaxGapSteps * T;
  Eigen::Index widest = 1;
  for (Eigen::Index k = 2; k < t.size(); ++k)
    if (t(k) - t(k - 1) > t(widest) - t(widest - 1)) widest = k;
  const double widest_step = t(widest) - t(widest - 1);
  if (widest_step > max_gap)
    throw Error("a gap of " + number_text(widest_step) + " s at t = " + number_text(t(widest - 1)) + " s (rows " +
                std::to_string(widest) + " to " + std::to_string(widest + 1) + ") is longer than the " +
                number_text(max_gap) + " s resampling accepts (--max-gap; default " + number_text(kDefaultMaxGapSteps) +
                " sample times); refusing to interpolate across it");
  const Eigen::Index rows = t.size();
  const double widest_at = t(widest - 1);
  resample_linear(t, values, T);
  result.steps.push_back("resampled " + std::to_string(rows) + " rows onto " + std::to_string(t.size()) +
                         " samples every " + number_text(T) +
                         " s by linear interpolation between neighbouring rows (first non-uniform step: " + where +
                         "; widest step " + number_text(widest_step) + " s from t = " + number_text(widest_at) +
                         " s, limit " + number_text(max_gap) + " s)");
}

void reconstruct_excitation(Experiment& e, ImportResult& result) {
  if (!e.controller) throw Error("--reconstruct-r needs the controller: give a template sidecar with `controller`");
  if (e.r_names.empty())
    for (const auto& u : e.u_names) e.r_names.push_back("r_" + u);
  const std::vector<std::string> r_names = std::move(e.r_names);
  e.r_names.clear();
  e.r.resize(0, 0);
  for (const auto& in : e.controller->inputs)
    if (std::find(r_names.begin(), r_names.end(), in) != r_names.end())
      throw Error("--reconstruct-r: the controller reads the excitation '" + in +
                  "' itself, so r cannot be computed from u");
  const ControllerReplay replay = replay_controller(e);
  e.r_names = r_names;
  // u = uf + r in deviations (experiment-format.md).
  e.r = (e.u_deviation() - replay.output).rowwise() + e.operating_values(e.r_names).transpose();
  result.clamped = replay.clamped;
  result.clamped_samples = replay.clamped_samples;
  result.steps.push_back(join(e.r_names) + " reconstructed as u - controller output (replayed from y, u); " +
                         std::to_string(replay.clamped_samples) + " of " + std::to_string(e.samples()) +
                         " samples have a controller clamp acting and are not exogenous");
}

ImportResult import_from(const RecordedColumns& columns, const ImportMapping& mapping, const ImportOptions& options,
                         const std::string& stem) {
  ImportResult result;
  result.file_kind = columns.kind();
  Experiment e;
  std::vector<SignalSource> y = mapping.y, u = mapping.u, r = mapping.r;
  if (options.reconstruct_r && !r.empty()) throw Error("--reconstruct-r computes r; the mapping must not map it");
  if (options.template_sidecar) {
    if (!options.plant_model.empty()) throw Error("give a template sidecar or a plant model, not both");
    e = *options.template_sidecar;
    y = in_order(y, e.y_names, "y");
    u = in_order(u, e.u_names, "u");
    if (!options.reconstruct_r) {
      if (!e.r_names.empty() || !r.empty()) r = in_order(r, e.r_names, "r");
    }
  } else {
    if (options.plant_model.empty()) throw Error("give a template sidecar or a plant model");
    if (options.reconstruct_r) throw Error("--reconstruct-r needs a template sidecar with the controller");
    e.plant.model = options.plant_model;
    e.y_names = names_of(y);
    e.u_names = names_of(u);
    e.r_names = names_of(r);
    e.extra = JsonValue::object();
  }
  e.name = !options.name.empty() ? options.name : options.template_sidecar ? e.name : stem;

  // Columns: t (if mapped), then y, u, r as SI values.
  std::vector<const SignalSource*> order;
  if (mapping.t) order.push_back(&*mapping.t);
  for (const auto* group : {&y, &u, &r})
    for (const auto& s : *group) order.push_back(&s);
  Eigen::MatrixXd table;
  for (std::size_t c = 0; c < order.size(); ++c) {
    const SignalSource& s = *order[c];
    const Eigen::VectorXd values = columns.column(s.source) * (s.scale * unit_factor(s.unit));
    if (c == 0) table.resize(values.size(), Eigen::Index(order.size()));
    if (values.size() != table.rows())
      throw Error("'" + s.source + "' (" + s.name + ") has " + std::to_string(values.size()) + " samples, '" +
                  order[0]->source + "' (" + order[0]->name + ") has " + std::to_string(table.rows()));
    table.col(Eigen::Index(c)) = values;
    result.steps.push_back(describe(s, result.file_kind));
  }
  result.rows = table.rows();
  if (result.rows < 2) throw Error("has " + std::to_string(result.rows) + " samples; at least 2 are needed");

  double T = options.sample_time > 0.0   ? options.sample_time
             : mapping.sample_time > 0.0 ? mapping.sample_time
             : options.template_sidecar  ? e.sample_time
                                         : 0.0;
  const char* T_source = options.sample_time > 0.0   ? "given"
                         : mapping.sample_time > 0.0 ? "from the mapping"
                         : options.template_sidecar  ? "from the template"
                                                     : "the median step of t";
  Eigen::MatrixXd values;
  Eigen::VectorXd t;
  if (mapping.t) {
    t = table.col(0);
    values = table.rightCols(table.cols() - 1);
    if (T == 0.0) T = median_step(t);
    if (!(T > 0.0)) throw Error("time is not strictly increasing (its median step is " + number_text(T) + " s)");
    result.steps.push_back("sample time " + number_text(T) + " s (" + T_source + ")");
    uniform_time(t, values, T, options, result);
  } else {
    if (T == 0.0) throw Error("the mapping names no time column; give the sample time");
    values = table;
    t.resize(table.rows());
    for (Eigen::Index k = 0; k < t.size(); ++k) t(k) = double(k) * T;
    result.steps.push_back("sample time " + number_text(T) + " s (" + T_source + "; no time column: t = k T)");
  }
  e.sample_time = T;
  if (e.controller && options.template_sidecar && std::abs(e.controller->sample_time - T) > 1e-9 * T)
    throw Error("the sample time " + number_text(T) + " s differs from the template controller's " +
                number_text(e.controller->sample_time) + " s");

  const auto ny = Eigen::Index(y.size()), nu = Eigen::Index(u.size()), nr = Eigen::Index(r.size());
  e.t = t;
  e.y = values.leftCols(ny);
  e.u = values.middleCols(ny, nu);
  e.r = values.rightCols(nr);
  if (!options.template_sidecar) {
    // No nominal model to say where the equilibrium is: the record's means stand for it.
    for (const auto* names : {&e.y_names, &e.u_names})
      for (const auto& n : *names) e.operating_point[n] = e.signal(n).mean();
    e.extra.json()["operating_point_source"] = "measured";
    result.steps.push_back("operating point: the mean of each y and u signal over the record (no template)");
  }
  if (options.reconstruct_r) {
    reconstruct_excitation(e, result);
  } else {
    const ControllerReplay clamps = clamped_samples(e);
    result.clamped = clamps.clamped;
    result.clamped_samples = clamps.clamped_samples;
  }
  e.validate();
  result.experiment = std::move(e);
  return result;
}

}  // namespace

ImportResult import_experiment(const std::filesystem::path& file, const ImportMapping& mapping,
                               const ImportOptions& options) {
  try {
    if (!std::filesystem::is_regular_file(file)) throw Error("no such file");
    const auto columns = is_mat_file(file) ? open_mat_columns(file) : open_csv_columns(file);
    return import_from(*columns, mapping, options, file.stem().string());
  } catch (const Error& e) {
    throw Error(file.string() + ": " + e.what());
  }
}

}  // namespace ambid
