#include "services/daemons/frf_daemon.hpp"

#include <cmath>
#include <optional>
#include <thread>

#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "services/convert/frequency_response.hpp"
#include "services/daemons/daemon_runtime.hpp"
#include "services/daemons/window_steps.hpp"

namespace ambid::daemons {
namespace {

struct FrfConfig {
  double duration = 1.0;  // s of samples analysed: one record of the plant
  bus::ExcitationCommand excitation, restore;
  double interval = 0.0;
};

FrfConfig frf_config(const nlohmann::json& j) {
  reject_unknown_keys(
      j, "frf config",
      {"duration", "excitation", "amplitude", "f_min", "f_max", "interval", "restore_excitation", "restore_amplitude"});
  FrfConfig c;
  c.duration = config_value(j, "duration", c.duration);
  if (!(c.duration > 0)) throw Error("frf config: duration must be > 0 s, got " + std::to_string(c.duration));
  c.excitation.kind = config_value<std::string>(j, "excitation", "multisine");
  c.excitation.amplitude = config_value(j, "amplitude", 0.05);
  c.excitation.frequencies = {config_value(j, "f_min", 1.0), config_value(j, "f_max", 1000.0)};
  c.restore.kind = config_value<std::string>(j, "restore_excitation", "prbs");
  c.restore.amplitude = config_value(j, "restore_amplitude", 0.05);
  c.interval = config_value(j, "interval", c.interval);
  return c;
}

}  // namespace

int run_frf_daemon(const DaemonOptions& options) {
  FrfConfig config = frf_config(load_config(options.config));
  config.excitation.plant_id = config.restore.plant_id = options.plant_id;

  auto bus = options.connect();
  DaemonRuntime runtime(*bus, "frf", options.plant_id + "/frf", options.metrics_port);
  auto samples = bus->reader<bus::PlantSamples>();
  auto descriptions = bus->reader<bus::PlantDescription>();
  auto commands = bus->writer<bus::ExcitationCommand>();
  auto responses = bus->writer<bus::FrequencyResponse>();
  runtime.ready(config.excitation.kind + " experiments of " + std::to_string(config.duration) +
                " s; plant description from the bus");
  WindowSteps steps(runtime, "samples that reached no frequency response");
  std::optional<bus::PlantDescription> description;  // the plant's latest

  std::uint64_t seq = 0;
  auto next_experiment = std::chrono::steady_clock::now();
  bool scheduled = true;  // another experiment is due at next_experiment
  bool commanded = false;
  int records_started = 0;  // the excitation is asked for; the next record of the plant is ours
  std::optional<DescribedWindows> window;
  while (runtime.running()) {
    bus->wait(std::chrono::milliseconds(100));
    for (const bus::PlantDescription& d : descriptions->take()) {
      if (d.plant_id != options.plant_id) continue;
      description = d;
      if (window) steps.describe(*window, d);
    }
    if (!commanded && scheduled && std::chrono::steady_clock::now() >= next_experiment && commands->matched()) {
      std::this_thread::sleep_for(std::chrono::milliseconds(500));  // let the plant's reader match us too
      config.excitation.seq = ++seq;
      commands->write(config.excitation);
      runtime.metrics.published.Increment();
      commanded = true;
      records_started = 0;
      window.reset();
    }
    for (const bus::PlantSamples& b : samples->take()) {
      if (b.plant_id != options.plant_id || !commanded) continue;
      runtime.metrics.received.Increment();
      // The first record to start after the command may have been simulated before the plant
      // took it; the one after is surely excited.
      if (b.seq == 0 && ++records_started == 2) {
        window.emplace(WindowSettings{.window = config.duration});
        if (description) steps.describe(*window, *description);
      }
      if (!window) continue;
      steps.report(window->add(b));
      if (!window->full()) continue;
      Experiment e = window->take();
      commanded = false;
      window.reset();
      config.restore.seq = ++seq;
      commands->write(config.restore);
      scheduled = config.interval > 0;
      next_experiment =
          std::chrono::steady_clock::now() + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                                 std::chrono::duration<double>(config.interval));
      try {
        // The band this daemon excited: the description on the bus says nothing of the excitation.
        ident::FrfAnalysisOptions analysis;
        analysis.f_min = config.excitation.frequencies.at(0);
        analysis.f_max = config.excitation.frequencies.at(1);
        responses->write(
            convert::to_message(ident::analyse_frf(e, analysis), options.plant_id, seq, e.t(e.samples() - 1)));
        runtime.metrics.published.Increment();
        runtime.log("frequency response of the record ending at " + std::to_string(e.t(e.samples() - 1)) + " s");
      } catch (const Error& err) {
        runtime.metrics.rejected.Increment();
        runtime.log("record ending at " + std::to_string(e.t(e.samples() - 1)) + " s not analysed: " + err.what());
      }
      break;
    }
  }
  return 0;
}

}  // namespace ambid::daemons
