// `ambid diagnose`: offline diagnosis over a time-ordered list of experiments or model files
// (a directory stands for its experiment sidecars and model files, in name order), all of one
// plant family: the family brings its monitored parameters, fault signatures, window length
// and window method (diagnostics/plant_families.hpp). Each experiment is cut into windows and
// every window is identified (diagnostics/experiment_windows.hpp identify_experiment_windows;
// amb1dof_voltage: pem by default, consistent at real sensor noise and off nominal, with sigmas;
// the baseline's learned window-to-window scatter widens them where they fall short; deadbeat
// is biased off nominal; maglev1coil_voltage: greybox, 3 s windows). A model file is one
// window. Fault isolation uses the closed-loop signatures of the first experiment's plant and
// controller (diagnostics/fault_signatures.hpp, maglev_fault_signatures.hpp). The windows of the
// first N inputs form the baseline, learned by the
// diagnostics engine (its mean and the scatter the reported sigmas do not explain). Writes DIR/diagnosis.json (the
// alerts, fields of experiment-format.md "Diagnosis"), DIR/summary.txt, DIR/trend_<parameter>.svg and the trend store
// DIR/trends.sqlite.
//
// Time: the experiment contract has no time key, so inputs are laid end to end in the order
// given: an experiment lasts its windows, a model file 1 s; a window's time is its end.
//
// A window that cannot be identified (ident::window_failure: too little excitation, a model
// without a continuous-time equivalent, ...), or a model file without a continuous part, is
// skipped, never the end of the run: said on stderr, counted by reason in diagnosis.json
// ("skipped_windows", and each input's "skipped" list) and in summary.txt.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "core/experiment_file.hpp"
#include "core/experiment_io.hpp"
#include "core/json_text.hpp"
#include "core/model_file.hpp"
#include "core/no_continuous_equivalent.hpp"
#include "diagnostics/experiment_windows.hpp"
#include "diagnostics/identified_estimates.hpp"
#include "diagnostics/offline_diagnosis.hpp"
#include "diagnostics/plant_families.hpp"
#include "identifier/identify_window.hpp"
#include "identifier/methods.hpp"
#include "services/cli/commands.hpp"
#include "services/cli/progress.hpp"
#include "services/report/figure.hpp"
#include "services/report/output_lock.hpp"
#include "services/report/svg.hpp"

namespace ambid::cli {
namespace {

constexpr double kModelDuration = 1.0;  // s a model file occupies on the time axis

struct DiagnoseArguments {
  std::vector<std::string> inputs;
  std::size_t baseline = 3;
  std::optional<double> window;       // empty: the family's
  std::optional<std::string> method;  // empty: the family's
  std::string family;                 // the first input's plant model
  std::string plant_id = "plant";
  std::string out;
  bool quiet = false;  // no progress line on stderr
};

using Skipped = diag::SkippedWindow;

struct Input {
  std::string file;
  std::string kind;  // "experiment" | "model"
  std::vector<diag::EstimateWindow> windows;
  std::vector<Skipped> skipped;
  double time_to = 0.0;              // end of its last window, identified or skipped
  std::optional<Experiment> loop;    // an experiment's sidecar (no samples): plant and controller
  Eigen::Index clamped_samples = 0;  // samples where a controller clamp acted (not exogenous)
};

void report_skipped(const std::string& file, const Skipped& s, std::size_t windows) {
  std::cerr << "ambid diagnose: " << file << ": window " << s.window << " of " << windows << " (to t = " << s.time
            << " s) skipped, not identified (" << s.failure.reason << "): " << s.failure.message << "\n";
}

bool is_model_file(const std::filesystem::path& path) {
  if (path.extension() != ".json") return false;
  nlohmann::json j;
  try {
    j = parse_json_text(read_json_file(path));
  } catch (const Error& e) {
    throw Error(path.string() + ": " + e.what());
  }
  return j.is_object() && j.contains("format") && j["format"] == kModelFormat;
}

// The family of the inputs: every input's plant model must be the first's.
void require_family(const std::string& file, const std::string& model, const std::string& family) {
  try {
    diag::require_diagnostics_piece(model, diag::DiagnosticsPiece::fault_signatures, "diagnose");
  } catch (const Error& e) {
    throw Error(file + ": plant model is '" + model + "': " + e.what());
  }
  if (model != family)
    throw Error(file + ": plant model is '" + model + "', the first input's is '" + family +
                "': one diagnosis watches one plant family");
}

Input model_input(const std::string& file, double start, const std::string& plant_id, const std::string& family) {
  const Model m = read_model(file);
  require_family(file, m.plant_model, family);
  Input in{file, "model", {}, {}, start + kModelDuration, std::nullopt};
  if (!m.no_continuous.empty()) {  // a valid discrete model without physical parameters
    in.skipped.push_back(
        {1, in.time_to,
         ident::window_failure(NoContinuousEquivalent("the model has no continuous part, so no physical parameters (" +
                                                      m.no_continuous + ")"))});
    report_skipped(in.file, in.skipped.back(), 1);
    return in;
  }
  try {
    in.windows.push_back(
        diag::estimate_window(m.plant_model, m.physical, m.uncertainty, in.time_to, plant_id, diag::Source::replay));
  } catch (const Error& e) {
    throw Error(file + ": " + e.what());
  }
  return in;
}

Input experiment_input(const std::string& file, double start, double window, const std::string& method,
                       const std::string& plant_id, const std::string& family, Progress& progress) {
  const ReadResult read = read_experiment(file);
  const Experiment& e = read.experiment;
  require_family(file, e.plant.model, family);
  const double length = double(e.samples()) * e.sample_time;
  const Eigen::Index samples = window > 0.0 ? Eigen::Index(std::lround(window / e.sample_time)) : e.samples();
  Input in{file, "experiment", {}, {}, start, e, read.clamped_samples};
  in.loop->t.resize(0);
  in.loop->y.resize(0, 0);
  in.loop->u.resize(0, 0);
  in.loop->r.resize(0, 0);
  diag::WindowCallbacks callbacks;
  callbacks.progress = [&](std::size_t done, std::size_t total) {
    progress.update("identify the windows of " + file, done, total);
  };
  callbacks.skipped = [&](const Skipped& s, std::size_t total) {
    progress.clear();
    report_skipped(file, s, total);
  };
  diag::ExperimentWindows identified;
  try {
    identified =
        diag::identify_experiment_windows(e, samples, method, start, plant_id, diag::Source::replay, callbacks);
  } catch (const Error& err) {  // what no window of this record could get past is an error of the input
    throw Error(file + " (" + std::to_string(length) + " s): " + err.what());
  }
  in.windows = std::move(identified.windows);
  in.skipped = std::move(identified.skipped);
  in.time_to = identified.time_to;
  return in;
}

std::string number(double v) {
  std::ostringstream s;
  s.precision(6);
  s << v;
  return s.str();
}

// Skipped windows by reason, every reason listed (0 for one that did not occur).
std::map<std::string, std::size_t> skipped_by_reason(const std::vector<Input>& inputs) {
  std::map<std::string, std::size_t> count;
  for (const std::string& reason : ident::window_failure_reasons()) count[reason] = 0;
  for (const Input& in : inputs)
    for (const Skipped& s : in.skipped) ++count[s.failure.reason];
  return count;
}

std::size_t skipped_total(const std::vector<Input>& inputs) {
  std::size_t n = 0;
  for (const Input& in : inputs) n += in.skipped.size();
  return n;
}

nlohmann::json diagnosis_json(const DiagnoseArguments& a, const std::vector<Input>& inputs,
                              std::size_t baseline_windows, const diag::OfflineDiagnosis& d) {
  nlohmann::json j;
  j["format"] = "ambid-diagnosis/1";
  j["plant_id"] = a.plant_id;
  j["plant_model"] = a.family;
  j["method"] = a.method.value_or("");
  j["window"] = a.window.value_or(0.0);
  j["baseline_inputs"] = a.baseline;
  j["baseline_windows"] = baseline_windows;
  j["skipped_windows"] = {{"count", skipped_total(inputs)}, {"reasons", skipped_by_reason(inputs)}};
  j["inputs"] = nlohmann::json::array();
  for (const Input& in : inputs) {
    nlohmann::json skipped = nlohmann::json::array();
    for (const Skipped& s : in.skipped)
      skipped.push_back(
          {{"window", s.window}, {"time", s.time}, {"reason", s.failure.reason}, {"message", s.failure.message}});
    j["inputs"].push_back({{"file", in.file},
                           {"kind", in.kind},
                           {"windows", in.windows.size()},
                           {"skipped", skipped},
                           {"time_to", in.time_to},
                           {"clamped_samples", in.clamped_samples}});
  }
  for (const auto& [key, b] : d.baselines)
    j["baselines"][key.second] = {{"mean", b.mean},
                                  {"extra_spread", b.extra_spread},
                                  {"mean_sigma", b.mean_sigma},
                                  {"reported_sigma", b.reported_sigma},
                                  {"windows", b.windows}};
  for (const auto& [key, level] : d.final_levels) j["levels"][key.second] = diag::to_string(level);
  j["alerts"] = nlohmann::json::array();
  for (const diag::Alert& alert : d.alerts) j["alerts"].push_back(diag::to_json(alert));
  return j;
}

std::string summary_text(const DiagnoseArguments& a, const std::vector<Input>& inputs, std::size_t baseline_windows,
                         const diag::OfflineDiagnosis& d) {
  std::ostringstream s;
  s << "ambid diagnose: plant '" << a.plant_id << "' (" << a.family << ", windows of " << number(a.window.value_or(0.0))
    << " s by " << a.method.value_or("") << "), " << inputs.size() << " inputs; baseline: the first " << a.baseline
    << " (" << baseline_windows << " windows)\n\n";
  for (const Input& in : inputs)
    s << "  " << in.kind << " " << in.file << ": " << in.windows.size() << " window(s)"
      << (in.skipped.empty() ? std::string() : ", " + std::to_string(in.skipped.size()) + " skipped")
      << ", to t = " << number(in.time_to) << " s"
      << (in.clamped_samples
              ? ", " + std::to_string(in.clamped_samples) +
                    " samples with a controller clamp acting (not exogenous: left out of the window fits and scores, "
                    "except by a method fitting the plant's own equations, e.g. greybox, which keeps them)"
              : std::string())
      << "\n";
  if (const std::size_t n = skipped_total(inputs); n > 0) {
    s << "\n  " << n << " window(s) skipped, not identified:";
    for (const auto& [reason, count] : skipped_by_reason(inputs))
      if (count > 0) s << " " << reason << " " << count;
    s << " (stderr and diagnosis.json name each)\n";
  }
  s << "\n  parameter  level  baseline      extra spread  latest\n";
  for (const auto& [key, level] : d.final_levels) {
    const diag::Baseline& b = d.baselines.at(key);
    double latest = 0.0;
    for (const Input& in : inputs)
      for (const diag::EstimateWindow& w : in.windows)
        for (const diag::ParameterEstimate& e : w.estimates)
          if (e.parameter == key.second) latest = e.value;
    char row[160];
    std::snprintf(row, sizeof row, "  %-9s  %-5s  %-12.6g  %-12.3g  %.6g\n", key.second.c_str(),
                  std::string(diag::to_string(level)).c_str(), b.mean, b.extra_spread, latest);
    s << row;
  }
  s << "\nalerts (" << d.alerts.size() << "):\n";
  if (d.alerts.empty()) s << "  none\n";
  for (const diag::Alert& alert : d.alerts)
    s << "  t = " << number(alert.time) << " s  " << diag::to_string(alert.level) << "  " << alert.fault
      << (alert.channel ? " channel " + std::to_string(*alert.channel) : std::string()) << "  " << alert.parameter
      << ": " << alert.message << "\n";
  s << "\nDetection works on z = (estimate - baseline mean) / sigma_eff with sigma_eff = sqrt(sigma^2 + extra^2):\n"
       "the identifier's one-sigma widened by the scatter of the baseline windows it does not explain.\n";
  return s.str();
}

// trend_PARAMETER.svg per parameter: (path, SVG text).
std::vector<std::pair<std::filesystem::path, std::string>> trend_plots(const std::filesystem::path& dir,
                                                                       const std::vector<Input>& inputs,
                                                                       std::size_t baseline_windows,
                                                                       const diag::OfflineDiagnosis& d,
                                                                       double error_fraction) {
  std::vector<std::pair<std::filesystem::path, std::string>> files;
  for (const auto& [key, b] : d.baselines) {
    std::vector<double> tb, vb, tm, vm;
    std::size_t n = 0;
    for (const Input& in : inputs)
      for (const diag::EstimateWindow& w : in.windows)
        for (const diag::ParameterEstimate& e : w.estimates) {
          if (e.parameter != key.second) continue;
          (n < baseline_windows ? tb : tm).push_back(w.time);
          (n < baseline_windows ? vb : vm).push_back(e.value);
          ++n;
        }
    report::Axes axes;
    axes.x_label = "time [s]";
    axes.y_label = key.second;
    axes.series = {report::markers("baseline windows", tb, vb), report::markers("diagnosed windows", tm, vm)};
    axes.reference_lines.push_back({b.mean, "baseline", "#444444", "4 3"});
    const std::string pct = number(100.0 * error_fraction);
    axes.reference_lines.push_back({b.mean * (1.0 + error_fraction), "+" + pct + " % (ERROR)", "#cc3333", "6 3"});
    axes.reference_lines.push_back({b.mean * (1.0 - error_fraction), "-" + pct + " % (ERROR)", "#cc3333", "6 3"});
    report::Figure figure;
    figure.title = key.first + ": " + key.second + " (" + std::string(diag::to_string(d.final_levels.at(key))) + ")";
    figure.height = 400.0;
    figure.axes = {axes};
    files.emplace_back(dir / ("trend_" + key.second + ".svg"), report::render_svg(figure));
  }
  return files;
}

void remove_store(const std::filesystem::path& store) {
  for (const char* suffix : {"", "-wal", "-shm"}) std::filesystem::remove(store.string() + suffix);
}

// The inputs with each directory replaced by its experiment sidecars and model files (*.json)
// in name order.
std::vector<std::string> expand_directories(const std::vector<std::string>& given) {
  std::vector<std::string> out;
  for (const std::string& input : given) {
    if (!std::filesystem::is_directory(input)) {
      out.push_back(input);
      continue;
    }
    std::vector<std::string> files;
    for (const auto& entry : std::filesystem::directory_iterator(input))
      if (entry.is_regular_file() && entry.path().extension() == ".json") files.push_back(entry.path().string());
    if (files.empty()) throw Error(input + ": a directory without experiments or model files (*.json)");
    std::sort(files.begin(), files.end());
    out.insert(out.end(), files.begin(), files.end());
  }
  return out;
}

// The plant model of an input (a model file's plant_model, an experiment's plant.model).
std::string plant_model_of(const std::string& file) {
  if (!std::filesystem::exists(file)) throw Error(file + ": no such file");
  return is_model_file(file) ? read_model(file).plant_model : read_experiment(file).experiment.plant.model;
}

void run(DiagnoseArguments a) {
  a.inputs = expand_directories(a.inputs);
  if (a.baseline >= a.inputs.size())
    throw Error("--baseline " + std::to_string(a.baseline) + " leaves nothing to diagnose: " +
                std::to_string(a.inputs.size()) + " input(s) given, more than the baseline are needed");
  a.family = plant_model_of(a.inputs.front());
  const std::string& family = a.family;
  require_family(a.inputs.front(), family, family);
  const diag::MonitoredFamily& watched = diag::monitored_family(family, "diagnose");
  const double window = a.window.value_or(watched.window);
  const std::string method = a.method.value_or(std::string(watched.window_method));
  a.window = window;
  a.method = method;
  if (!(window >= 0.0) || !std::isfinite(window))
    throw Error("--window must be 0 (whole experiment) or a positive number of seconds, got " + number(window));
  Progress progress("ambid diagnose", a.quiet);
  std::vector<Input> inputs;
  double start = 0.0;
  for (const std::string& file : a.inputs) {
    if (!std::filesystem::exists(file)) throw Error(file + ": no such file");
    inputs.push_back(is_model_file(file) ? model_input(file, start, a.plant_id, family)
                                         : experiment_input(file, start, window, method, a.plant_id, family, progress));
    start = inputs.back().time_to;
  }
  std::size_t baseline_windows = 0;
  std::vector<diag::EstimateWindow> windows;
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    if (i < a.baseline) baseline_windows += inputs[i].windows.size();
    windows.insert(windows.end(), inputs[i].windows.begin(), inputs[i].windows.end());
  }
  if (baseline_windows < diag::kMinLearningWindows)
    throw Error("the first " + std::to_string(a.baseline) + " input(s) give " + std::to_string(baseline_windows) +
                " identified window(s) (" + std::to_string(skipped_total(inputs)) +
                " window(s) of all inputs skipped, see above); the baseline needs at least " +
                std::to_string(diag::kMinLearningWindows) + " (a shorter --window or a larger --baseline)");
  if (windows.size() == baseline_windows)
    throw Error("no window after the baseline was identified (" + std::to_string(skipped_total(inputs)) +
                " window(s) skipped, see above): nothing left to diagnose");
  const std::filesystem::path dir(a.out);
  const report::OutputLock lock(dir);
  diag::EngineConfig config;
  config.isolation.family = family;
  // Fault signatures of the loop the records came from (the first experiment's plant and
  // controller); model files alone get those of the family's default loop (`ambid sim`).
  for (const Input& in : inputs) {
    if (!in.loop) continue;
    try {
      config.isolation.hypotheses = diag::fault_hypotheses(*in.loop);
    } catch (const Error& e) {
      throw Error(in.file + ": no fault signatures of its closed loop: " + e.what());
    }
    break;
  }
  // The new trend store is built beside the old one and every output is complete before any
  // replaces its predecessor: a failed run (a full disk) leaves the previous run's files as they were.
  const std::filesystem::path store = dir / "trends.sqlite", fresh = dir / ".trends.sqlite.new";
  diag::OfflineDiagnosis d;
  progress.update("learn the baseline and diagnose the windows", 0, 1);
  try {
    d = diag::diagnose_offline(windows, baseline_windows, fresh, config);
  } catch (...) {
    remove_store(fresh);
    throw;
  }
  progress.clear();
  const std::string summary = summary_text(a, inputs, baseline_windows, d);
  std::vector<std::pair<std::filesystem::path, std::string>> files = {
      {dir / "diagnosis.json", diagnosis_json(a, inputs, baseline_windows, d).dump(2) + "\n"},
      {dir / "summary.txt", summary}};
  for (auto& plot : trend_plots(dir, inputs, baseline_windows, d, config.policy.error_fraction))
    files.push_back(std::move(plot));
  try {
    write_files_atomically(files);
  } catch (...) {
    remove_store(fresh);
    throw;
  }
  remove_store(store);  // with its journal files, which must not be applied to the new store
  std::filesystem::rename(fresh, store);
  std::cout << summary << "wrote " << (dir / "diagnosis.json").string()
            << ", summary.txt, trend_*.svg, trends.sqlite\n";
}

}  // namespace

void add_diagnose_command(CLI::App& app) {
  auto args = std::make_shared<DiagnoseArguments>();
  CLI::App* cmd = app.add_subcommand("diagnose", "diagnose a time-ordered list of experiments or model files");
  cmd->add_option("inputs", args->inputs,
                  "experiments (.json sidecar, .csv or stem), model.json files or directories of them, oldest first")
      ->required();
  cmd->add_option("--baseline", args->baseline, "how many of the first inputs form the baseline")
      ->capture_default_str();
  cmd->add_option("--window", args->window,
                  "window length (s) each experiment is cut into; 0: one window each (default: the plant family's, "
                  "amb1dof_voltage 0.25, maglev1coil_voltage 3)");
  cmd->add_option("--method", args->method,
                  "identification of each window: " + ident::method_names(" | ") +
                      " (below; default: the plant family's, amb1dof_voltage pem, maglev1coil_voltage greybox); "
                      "closed-loop reports no sigma (the baseline scatter is used), deadbeat does but is biased off "
                      "nominal");
  cmd->footer("--method:\n" + ident::method_table());
  cmd->add_option("--plant-id", args->plant_id, "plant id in the alerts")->capture_default_str();
  cmd->add_option("--out", args->out, "output directory")->required();
  cmd->add_flag("--quiet", args->quiet, "no progress line on stderr (there is none when stderr is no terminal)");
  cmd->callback([args] { run(*args); });
}

}  // namespace ambid::cli
