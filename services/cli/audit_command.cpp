// `ambid audit EXPERIMENT.json --out DIR`: where the nominal simulation of a measured machine
// is wrong, which effect explains it, and the gain of the extended model (diagnostics/audit.hpp).
// Writes DIR/audit.json, DIR/model-extended.json and DIR/report.html.
#include <filesystem>
#include <iostream>
#include <memory>

#include <nlohmann/json.hpp>

#include "core/experiment_file.hpp"
#include "core/experiment_io.hpp"
#include "diagnostics/audit.hpp"
#include "services/cli/audit_report.hpp"
#include "services/cli/commands.hpp"
#include "services/cli/progress.hpp"
#include "services/report/output_lock.hpp"

namespace ambid::cli {
namespace {

struct AuditArguments {
  std::string experiment;
  std::string out;
  diag::AuditOptions options;
  bool quiet = false;  // no progress line on stderr
};

}  // namespace

void add_audit_command(CLI::App& app) {
  auto args = std::make_shared<AuditArguments>();
  CLI::App* audit = app.add_subcommand(
      "audit", "compare the nominal model with a measured experiment, name the missing effect, fit it");
  audit->add_option("experiment", args->experiment, "experiment (.json sidecar, .csv or stem)")->required();
  audit->add_option("--out", args->out, "output directory: audit.json, model-extended.json, report.html")->required();
  audit
      ->add_option("--estimation-fraction", args->options.estimation_fraction,
                   "leading part of the record used for fitting; the rest validates")
      ->capture_default_str();
  audit
      ->add_option("--false-acceptance", args->options.false_acceptance,
                   "probability of naming a cause when the nominal model is right (noise only)")
      ->capture_default_str();
  audit
      ->add_option("--fitted-candidates", args->options.fitted_candidates,
                   "how many of the screened candidates are fitted")
      ->capture_default_str();
  audit->add_flag("--quiet", args->quiet, "no progress line on stderr (there is none when stderr is no terminal)");
  audit->callback([args] {
    const report::OutputLock lock(args->out);
    Progress progress("ambid audit", args->quiet);
    progress.update("read " + args->experiment, 0, 1);
    const ReadResult read = read_experiment(args->experiment);
    progress.clear();
    for (const auto& w : read.warnings) std::cerr << "ambid audit: warning: " << w << "\n";
    diag::AuditOptions options = args->options;
    options.progress = [&progress](const std::string& stage, std::size_t done, std::size_t total) {
      progress.update(stage, done, total);
    };
    const diag::AuditResult result = diag::run_audit(read.experiment, options);
    progress.clear();
    const std::filesystem::path dir(args->out);
    const std::string experiment_file = std::filesystem::path(args->experiment).filename().string();
    // All three rendered before any is written: a failure leaves the previous outputs, no new one.
    write_files_atomically(
        {{dir / "audit.json", diag::audit_json(result, experiment_file, "model-extended.json").dump(2) + "\n"},
         {dir / "model-extended.json", diag::extended_model_json(read.experiment, result).dump(2) + "\n"},
         {dir / "report.html", audit_report_html(result, experiment_file)}});
    std::cout << "ambid audit: " << audit_verdict(result) << "\n";
    std::cout.precision(4);
    for (const auto& f : result.findings)
      std::cout << "  " << f.effect.name << (f.effect.channel ? " channel " + std::to_string(f.effect.channel) : "")
                << ": NRMSE " << f.nrmse_total_before << " -> " << f.nrmse_total_after
                << (f.accepted ? "  (cause)" : "") << "\n";
    if (result.clamped_samples > 0)
      std::cout << "  " << result.clamped_samples
                << " samples with a controller clamp acting (not exogenous): left out "
                << "of every fit, score and statistic (audit.json clamped_samples)\n";
    std::cout << "  wrote " << (dir / "audit.json").string() << ", model-extended.json and report.html\n";
  });
}

}  // namespace ambid::cli
