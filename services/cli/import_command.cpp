// `ambid import`: a record written by another tool (MAT v5 or CSV, own names, units, column
// order, with or without time) -> a contract experiment, printing what was done.
#include <iostream>
#include <memory>

#include "core/experiment_import.hpp"
#include "core/experiment_io.hpp"
#include "services/cli/commands.hpp"
#include "services/cli/progress.hpp"

namespace ambid::cli {
namespace {

struct ImportArguments {
  std::string file, out, mapping_file, template_file, t;
  std::vector<std::string> y, u, r;
  ImportOptions options;
  bool quiet = false;  // no progress line on stderr
};

ImportMapping mapping_of(const ImportArguments& a) {
  ImportMapping m = a.mapping_file.empty() ? ImportMapping{} : read_import_mapping(a.mapping_file);
  if (!a.t.empty()) m.t = parse_signal_source("t", a.t);
  const std::pair<const std::vector<std::string>*, std::vector<SignalSource>*> groups[] = {
      {&a.y, &m.y}, {&a.u, &m.u}, {&a.r, &m.r}};
  for (const auto& [texts, sources] : groups)
    for (const auto& text : *texts) sources->push_back(parse_signal_mapping(text));
  return m;
}

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out.empty() ? "none" : out;
}

}  // namespace

void add_import_command(CLI::App& app) {
  auto args = std::make_shared<ImportArguments>();
  auto& o = args->options;
  CLI::App* cmd = app.add_subcommand("import", "turn a MAT v5 or CSV record of another tool into an experiment");
  cmd->add_option("file", args->file, "the record (.mat or .csv with a header line)")->required();
  cmd->add_option("--out", args->out, "experiment to write (stem, .csv or .json)")->required();
  cmd->add_option("--template", args->template_file,
                  "contract sidecar whose plant, signals, operating point and controller the experiment takes");
  cmd->add_option("--plant", o.plant_model, "without --template: plant.model (operating point: the record's means)");
  cmd->add_option("--mapping", args->mapping_file,
                  "JSON file {\"t\": SPEC, \"y\": [\"NAME=SPEC\"], \"u\": [...], \"r\": [...], \"sample_time\": s}");
  cmd->add_option("--t", args->t, "time column or variable: SOURCE[:UNIT][*SCALE] (none: give --sample-time)");
  cmd->add_option("--y", args->y, "an output: NAME=SOURCE[:UNIT][*SCALE], e.g. x=pos:mm or x='A(:,2)*0.001'");
  cmd->add_option("--u", args->u, "a plant input: NAME=SOURCE[:UNIT][*SCALE]");
  cmd->add_option("--r", args->r, "an excitation: NAME=SOURCE[:UNIT][*SCALE]");
  cmd->add_option("--sample-time", o.sample_time,
                  "s (default: the mapping's, the template's, else the median step of t)");
  cmd->add_flag("--resample", o.resample,
                "non-uniform time: linear interpolation between neighbouring rows onto the uniform grid");
  cmd->add_option("--max-gap", o.max_gap,
                  "--resample refuses a step of t longer than this (s; default 10 sample times)");
  cmd->add_flag("--reconstruct-r", o.reconstruct_r,
                "r not logged: r = u - output of the template's controller; clamped samples are not exogenous");
  cmd->add_option("--name", o.name, "experiment name (default: the template's, else the file's stem)");
  cmd->add_flag("--quiet", args->quiet, "no progress line on stderr (there is none when stderr is no terminal)");
  cmd->footer("Units: " + import_units() + ". A value is raw * SCALE * unit factor.");
  cmd->callback([args] {
    Progress progress("ambid import", args->quiet);
    ImportOptions options = args->options;
    if (!args->template_file.empty()) options.template_sidecar = read_sidecar(args->template_file);
    progress.update("read and convert " + args->file, 0, 2);
    const ImportResult result = import_experiment(args->file, mapping_of(*args), options);
    progress.update("write " + args->out, 1, 2);
    write_experiment(result.experiment, args->out);
    progress.clear();
    const Experiment& e = result.experiment;
    std::cout << "ambid import: " << args->file << " (" << result.file_kind << ", " << result.rows << " rows)\n";
    for (const auto& step : result.steps) std::cout << "  " << step << "\n";
    std::cout << "  wrote " << args->out << ": " << e.samples() << " samples, t = " << e.t(0) << " to "
              << e.t(e.samples() - 1) << " s; y: " << joined(e.y_names) << "; u: " << joined(e.u_names)
              << "; r: " << joined(e.r_names) << "; clamped samples: " << result.clamped_samples << "\n";
  });
}

}  // namespace ambid::cli
