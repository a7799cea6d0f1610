// `ambid record --out STEM --duration S`: records the plant's samples from the bus into an
// experiment file. The sidecar is the plant description the samples name (PlantDescription on
// the bus): a recording replays with the controller and nominal parameters it was made with.
#include <iostream>
#include <memory>

#include "core/error.hpp"
#include "core/experiment_io.hpp"
#include "services/cli/operator_commands.hpp"
#include "services/daemons/daemon_options.hpp"
#include "services/daemons/described_windows.hpp"

namespace ambid::cli {
namespace {

struct RecordArguments {
  daemons::BusOptions bus;
  std::string out;
  double duration = 1.0, timeout = 30.0;
};

void run(const RecordArguments& args) {
  if (!(args.duration > 0)) throw Error("--duration must be > 0 s");
  daemons::DescribedWindows window({.window = args.duration});
  auto bus = args.bus.connect();
  auto samples = bus->reader<bus::PlantSamples>();
  auto descriptions = bus->reader<bus::PlantDescription>();
  std::uint64_t rejected = 0;
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(args.timeout);
  while (!window.full()) {
    if (std::chrono::steady_clock::now() > end)
      throw Error("recorded only " + std::to_string(window.buffered()) + " consecutive samples within " +
                  std::to_string(args.timeout) + " s");
    bus->wait(std::chrono::milliseconds(100));
    for (const auto& d : descriptions->take())
      if (d.plant_id == args.bus.plant_id) window.describe(d);
    for (const auto& b : samples->take()) {
      if (b.plant_id != args.bus.plant_id) continue;
      for (const auto& step : window.add(b)) rejected += step.event == daemons::DescribedWindows::Event::rejected;
    }
  }
  Experiment e = window.take();
  e.name = "recorded " + args.bus.plant_id;
  write_experiment(e, args.out);
  std::cout << "ambid record: " << e.samples() << " samples from t=" << e.t(0) << " s to " << args.out << ".csv/.json"
            << (rejected ? ", " + std::to_string(rejected) + " malformed batches skipped" : "") << std::endl;
}

}  // namespace

void add_record_command(CLI::App& app) {
  auto args = std::make_shared<RecordArguments>();
  CLI::App* c = app.add_subcommand("record", "record plant samples from the bus into an experiment file");
  daemons::add_bus_options(*c, args->bus);
  c->add_option("--out", args->out, "output stem: writes STEM.csv and STEM.json")->required();
  c->add_option("--duration", args->duration, "seconds of consecutive samples")->capture_default_str();
  c->add_option("--timeout", args->timeout, "give up after this many seconds")->capture_default_str();
  c->callback([args] { run(*args); });
}

}  // namespace ambid::cli
