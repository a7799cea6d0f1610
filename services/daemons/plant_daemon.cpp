#include "services/daemons/plant_daemon.hpp"

#include <algorithm>
#include <thread>

#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "core/experiment_io.hpp"
#include "services/convert/plant_description.hpp"
#include "services/convert/plant_samples.hpp"
#include "services/convert/source_kind.hpp"
#include "services/daemons/daemon_runtime.hpp"
#include "services/daemons/excitation_limits.hpp"
#include "services/daemons/plant_source.hpp"
#include "services/daemons/rig_source.hpp"

namespace ambid::daemons {
namespace {

struct PlantConfig {
  bus::SourceKind kind = bus::SourceKind::sim;
  std::string target;
  Eigen::Index batch_samples = 500;
  double speed = 10.0;
  ExcitationLimits excitation;
  RigSettings rig;
  std::string rig_description;  // sidecar JSON: the plant description of the rig's board
};

PlantConfig plant_config(const nlohmann::json& j) {
  reject_unknown_keys(j, "plant config",
                      {"source", "target", "batch_samples", "speed", "max_amplitude", "max_frequency", "rig_silence",
                       "rig_reply_timeout", "rig_allow_remote", "rig_description"});
  PlantConfig c;
  c.kind = convert::parse_source_kind(config_value<std::string>(j, "source", "sim"));
  c.target = config_value<std::string>(j, "target", "");
  c.batch_samples = config_value(j, "batch_samples", 500);
  c.speed = config_value(j, "speed", c.speed);
  c.excitation.max_amplitude = config_value(j, "max_amplitude", c.excitation.max_amplitude);
  c.excitation.max_frequency = config_value(j, "max_frequency", c.excitation.max_frequency);
  c.rig.silence = config_value(j, "rig_silence", c.rig.silence);
  c.rig.reply_timeout = config_value(j, "rig_reply_timeout", c.rig.reply_timeout);
  c.rig.allow_remote = config_value(j, "rig_allow_remote", c.rig.allow_remote);
  c.rig_description = config_value<std::string>(j, "rig_description", "");
  if (!(c.rig.silence > 0))
    throw Error("plant config: rig_silence must be > 0 s, got " + std::to_string(c.rig.silence));
  if (!(c.rig.reply_timeout > 0))
    throw Error("plant config: rig_reply_timeout must be > 0 s, got " + std::to_string(c.rig.reply_timeout));
  if (c.target.empty()) throw Error("plant config: 'target' (the scenario or experiment file) is required");
  if (c.batch_samples < 1 || c.batch_samples > 2000)
    throw Error("plant config: batch_samples must be 1..2000, got " + std::to_string(c.batch_samples));
  if (!(c.speed > 0)) throw Error("plant config: speed must be > 0, got " + std::to_string(c.speed));
  return c;
}

class PlantDaemon {
 public:
  PlantDaemon(const DaemonOptions& o, const PlantConfig& c)
      : options_(o),
        config_(c),
        bus_(o.connect()),
        runtime_(*bus_, "plant", o.plant_id + "/plant", o.metrics_port),
        samples_(bus_->writer<bus::PlantSamples>()),
        descriptions_(bus_->writer<bus::PlantDescription>()),
        state_(bus_->writer<bus::PlantSourceState>()),
        alerts_(bus_->writer<bus::Alert>()),
        source_commands_(bus_->reader<bus::PlantSourceCommand>()),
        excitation_commands_(bus_->reader<bus::ExcitationCommand>()),
        rig_description_(c.rig_description.empty() ? std::nullopt : std::optional(read_sidecar(c.rig_description))),
        source_(make_plant_source(c.kind, c.target, context())) {}

  int run() {
    announce(0, true, "started");
    runtime_.ready(std::string(convert::source_kind_name(source_->kind())) + " " + source_->target());
    while (runtime_.running()) {
      handle_commands();
      if (!source_) {  // failed with no fallback: commands only
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
        continue;
      }
      if (auto c = source_->condition_change()) {
        announce(last_source_command_, true, c->message);
        runtime_.set_health(c->ok ? bus::AlertLevel::ok : bus::AlertLevel::warn, c->message);
      }
      publish_batch();
      if (!source_ || source_->live()) continue;  // a live source waits for its samples in next_rows
      // Pace: the simulated time published since the source started, at `speed` times real time.
      const auto due = pace_start_ + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                         std::chrono::duration<double>((clock_ - pace_clock_) / config_.speed));
      std::this_thread::sleep_until(std::min(due, std::chrono::steady_clock::now() + std::chrono::milliseconds(200)));
    }
    return 0;
  }

 private:
  SourceContext context() {
    return {config_.batch_samples, config_.rig, &runtime_.metrics,
            [this](const std::string& line) { runtime_.log(line); }};
  }

  void publish_batch() {
    if (row_ >= record_.samples()) {
      std::optional<SourceRows> rows;
      try {
        rows = source_->next_rows(std::chrono::milliseconds(20));
      } catch (const Error& e) {
        source_failed(e.what());
        return;
      }
      if (!rows) return;
      record_ = std::move(rows->rows);
      row_ = 0;
      try {
        publish_description();
      } catch (const Error& e) {
        source_failed(e.what());
        return;
      }
      if (rows->starts_record) {
        record_offset_ = clock_ - record_.t(0);
        seq_ = 0;
      }
    }
    const Eigen::Index count = std::min(config_.batch_samples, record_.samples() - row_);
    bus::PlantSamples batch = convert::sample_batch(record_, row_, count, options_.plant_id, seq_++, record_offset_);
    batch.description_id = description_.description_id;
    samples_->write(batch);
    runtime_.metrics.published.Increment();
    row_ += count;
    clock_ = record_.t(row_ - 1) + record_offset_ + record_.sample_time;
  }

  // The description of the rows just taken (a rig's from the configured file); written when it
  // differs from the last one. Error when the source's rows cannot be described.
  void publish_description() {
    if (source_->kind() == bus::SourceKind::rig) {
      if (!rig_description_)
        throw Error("a rig's samples need a plant description: name its sidecar in the plant config (rig_description)");
      record_ = with_description(std::move(record_), *rig_description_);
    }
    bus::PlantDescription d = convert::describe(record_, options_.plant_id);
    if (d.description_id == description_.description_id) return;
    descriptions_->write(d);
    runtime_.metrics.published.Increment();
    runtime_.log("plant description " + d.description_id + " (" + d.model + ", controller " +
                 convert::controller_summary(d) + ")");
    description_ = std::move(d);
  }

  void handle_commands() {
    for (const bus::PlantSourceCommand& c : source_commands_->take()) {
      if (c.plant_id != options_.plant_id || c.seq == last_source_command_) continue;  // a resend
      last_source_command_ = c.seq;
      runtime_.metrics.received.Increment();
      try {
        std::unique_ptr<PlantSource> next = make_plant_source(c.kind, c.target, context());
        if (source_) previous_ = std::move(source_);
        source_ = std::move(next);
        row_ = record_.samples();  // the next batch starts a record of the new source
        pace_start_ = std::chrono::steady_clock::now();
        pace_clock_ = clock_;
        announce(c.seq, true, "source swapped");
        // A new source ends the WARN of a silent rig.
        runtime_.set_health(bus::AlertLevel::ok,
                            "source " + std::string(convert::source_kind_name(c.kind)) + " " + c.target);
      } catch (const Error& e) {
        runtime_.metrics.rejected.Increment();
        announce(c.seq, false, e.what());
      }
    }
    for (const bus::ExcitationCommand& c : excitation_commands_->take()) {
      if (c.plant_id != options_.plant_id) continue;
      runtime_.metrics.received.Increment();
      std::string refusal = source_ ? excitation_violation(c, config_.excitation) : "no source is running";
      if (refusal.empty()) {
        try {
          source_->excite(excitation_request(c));
        } catch (const Error& e) {
          refusal = e.what();
        }
      }
      if (refusal.empty()) {
        runtime_.log("excitation " + c.kind + " accepted (command " + std::to_string(c.seq) + ")");
        runtime_.set_health(bus::AlertLevel::ok, "excitation " + c.kind + " accepted");
      } else {
        runtime_.metrics.rejected.Increment();
        runtime_.log("excitation command " + std::to_string(c.seq) + " refused: " + refusal);
        runtime_.set_health(bus::AlertLevel::warn, "excitation refused: " + refusal);
      }
    }
  }

  // A source that fails after it was accepted (a later simulated record diverges, a replay
  // file vanished) stops; the daemon falls back to the source before it, or waits for the
  // next command. Health ERROR and an ERROR alert (source_failed) tell the operator either way.
  void source_failed(const std::string& reason) {
    const std::string message =
        "failed: " + reason +
        (previous_ ? "; back to the previous source" : "; no samples until the next source command");
    announce(last_source_command_, false, message);
    runtime_.set_health(bus::AlertLevel::error, "source " + source_->target() + " " + message);
    bus::Alert a;
    a.plant_id = options_.plant_id;
    a.fault = "source_failed";
    a.parameter = "source";
    a.level = bus::AlertLevel::error;
    a.time = clock_;
    a.message = ("source " + source_->target() + " " + message).substr(0, bus::limits::text_length);
    alerts_->write(a);
    runtime_.metrics.published.Increment();
    source_ = std::move(previous_);
    row_ = record_.samples();
    pace_start_ = std::chrono::steady_clock::now();
    pace_clock_ = clock_;
    if (source_) announce(last_source_command_, true, "resumed after the failure of the source that replaced it");
  }

  void announce(std::uint64_t command_seq, bool accepted, const std::string& message) {
    bus::PlantSourceState s;
    s.plant_id = options_.plant_id;
    s.time = clock_;
    s.kind = source_->kind();
    s.target = source_->target().substr(0, bus::limits::text_length);
    s.command_seq = command_seq;
    s.command_accepted = accepted;
    s.message = message.substr(0, bus::limits::text_length);
    state_->write(s);
    runtime_.metrics.published.Increment();
    runtime_.log((accepted ? "source " : "source command refused, still ") + s.target + ": " + message);
  }

  DaemonOptions options_;
  PlantConfig config_;
  std::unique_ptr<bus::Bus> bus_;
  DaemonRuntime runtime_;
  std::unique_ptr<bus::Writer<bus::PlantSamples>> samples_;
  std::unique_ptr<bus::Writer<bus::PlantDescription>> descriptions_;
  std::unique_ptr<bus::Writer<bus::PlantSourceState>> state_;
  std::unique_ptr<bus::Writer<bus::Alert>> alerts_;
  std::unique_ptr<bus::Reader<bus::PlantSourceCommand>> source_commands_;
  std::unique_ptr<bus::Reader<bus::ExcitationCommand>> excitation_commands_;
  std::optional<Experiment> rig_description_;
  bus::PlantDescription description_;      // the last one written
  std::unique_ptr<PlantSource> source_;    // null after a failure with nothing to fall back to
  std::unique_ptr<PlantSource> previous_;  // the source before the last swap (the fallback)
  Experiment record_;
  Eigen::Index row_ = 0;
  std::uint64_t seq_ = 0;
  std::uint64_t last_source_command_ = 0;
  double clock_ = 0.0;  // plant time of the next sample, continuous across records and sources
  double record_offset_ = 0.0;
  std::chrono::steady_clock::time_point pace_start_ = std::chrono::steady_clock::now();
  double pace_clock_ = 0.0;  // clock_ at pace_start_
};

}  // namespace

int run_plant_daemon(const DaemonOptions& options) {
  return PlantDaemon(options, plant_config(load_config(options.config))).run();
}

}  // namespace ambid::daemons
