#include "services/rig/rig_emulator.hpp"

#include <algorithm>

#include "core/error.hpp"
#include "services/rig/rig_frame.hpp"

namespace ambid::rig {
namespace {

using Clock = std::chrono::steady_clock;

double seconds(Clock::duration d) { return std::chrono::duration<double>(d).count(); }

class Emulator {
 public:
  Emulator(const EmulatorOptions& o, const std::function<void(const std::string&)>& log)
      : o_(o), log_(log), socket_(o.listen) {
    next_record();
    log_("rig emulator listening on " + socket_.local().text() + ", plant " + status().model + ", " +
         std::to_string(o_.speed) + "x real time");
  }

  void run(const std::function<bool()>& running) {
    while (running()) {
      const Clock::time_point now = Clock::now();
      if (start_) stream_until(seconds(now - *start_) * o_.speed);
      if (gateway_ && seconds(now - last_heard_) > o_.lease) {
        log_("gateway " + gateway_->text() + " silent for " + std::to_string(o_.lease) + " s: streaming stopped");
        gateway_.reset();
      }
      if (gateway_ && seconds(now - last_status_) >= 0.5) send_status();
      while (auto d = socket_.receive(std::chrono::milliseconds(start_ ? 2 : 100))) handle(*d);
    }
  }

 private:
  // The truth of the next record: the fault scenario once its time has come, with the last
  // accepted excitation.
  sim::ScenarioOptions current() const {
    sim::ScenarioOptions s = o_.fault && record_start_ >= o_.fault_at ? *o_.fault : o_.scenario;
    if (excitation_) {
      s.excitation = excitation_->kind;
      s.amplitude = excitation_->amplitude;
      if (excitation_->f_max > 0) {
        s.f_min = excitation_->f_min;
        s.f_max = excitation_->f_max;
      }
    }
    s.seed += record_;
    return s;
  }

  void next_record() {
    if (record_count_ > 0) {
      record_start_ += double(record_data_.samples()) * record_data_.sample_time;
      ++record_;
    }
    ++record_count_;
    const bool faulty = o_.fault && record_start_ >= o_.fault_at;
    if (faulty && !fault_logged_) {
      log_("record " + std::to_string(record_) + " at board time " + std::to_string(record_start_) +
           " s runs the fault scenario " + o_.fault->name);
      fault_logged_ = true;
    }
    try {
      record_data_ = sim::simulate_scenario(current());
    } catch (const Error& e) {  // e.g. an accepted excitation that makes the rotor touch down
      if (!excitation_) throw;
      log_("record " + std::to_string(record_) + " failed with the excitation " + excitation_->kind + " " +
           std::to_string(excitation_->amplitude) + " V (" + e.what() + "): the board runs on without it");
      excitation_.reset();
      record_data_ = sim::simulate_scenario(current());
    }
    row_ = 0;
  }

  // Sends (when a gateway holds the lease) every full frame of samples due by `board_now`,
  // and the last partial frame of a record; unsent samples of a board nobody listens to are lost.
  void stream_until(double board_now) {
    const Experiment& e = record_data_;
    const std::size_t per_frame =
        max_batch_samples(e.y_names.size(), e.u_names.size(), e.r_names.size(), e.plant.model.size());
    for (;;) {
      const Eigen::Index left = e.samples() - row_;
      if (left == 0) {
        next_record();
        continue;
      }
      const Eigen::Index n = std::min<Eigen::Index>(Eigen::Index(per_frame), left);
      if (record_start_ + e.t(row_ + n - 1) - e.t(0) > board_now) return;
      if (gateway_) send_batch(row_, n);
      row_ += n;
    }
  }

  void send_batch(Eigen::Index begin, Eigen::Index n) {
    const Experiment& e = record_data_;
    SampleBatch b;
    b.record = record_;
    b.first_index = std::uint64_t(begin);
    b.sample_time = e.sample_time;
    b.model = e.plant.model;
    b.ny = std::uint8_t(e.y.cols());
    b.nu = std::uint8_t(e.u.cols());
    b.nr = std::uint8_t(e.r.cols());
    for (Eigen::Index k = begin; k < begin + n; ++k) {
      b.t.push_back(record_start_ + e.t(k) - e.t(0));
      for (Eigen::Index j = 0; j < e.y.cols(); ++j) b.y.push_back(e.y(k, j));
      for (Eigen::Index j = 0; j < e.u.cols(); ++j) b.u.push_back(e.u(k, j));
      for (Eigen::Index j = 0; j < e.r.cols(); ++j) b.r.push_back(e.r(k, j));
    }
    send(b);
  }

  RigStatus status() const {
    RigStatus s;
    s.board_time = start_ ? seconds(Clock::now() - *start_) * o_.speed : 0.0;
    s.sample_time = record_data_.sample_time;
    s.model = record_data_.plant.model;
    s.y_names = record_data_.y_names;
    s.u_names = record_data_.u_names;
    s.r_names = record_data_.r_names;
    s.message = "record " + std::to_string(record_);
    return s;
  }

  void send_status() {
    send(status());
    last_status_ = Clock::now();
  }

  void send(const Payload& p) {
    if (!gateway_) return;
    socket_.send_to(*gateway_, encode(Frame{seq_++, p}));
  }

  void handle(const UdpSocket::Datagram& d) {
    const Decoded decoded = decode(d.bytes);
    if (!decoded.frame) {
      log_("datagram from " + d.from.text() + " rejected (" + std::string(fault_name(decoded.fault)) +
           "): " + decoded.reason);
      return;
    }
    const Payload& p = decoded.frame->payload;
    if (const auto* hello = std::get_if<Hello>(&p)) {
      if (gateway_ && !(*gateway_ == d.from)) {  // the session is the lease holder's until it lapses
        if (++refused_hellos_ <= 20 || refused_hellos_ % 1000 == 0)
          log_("HELLO from " + d.from.text() + " refused: " + gateway_->text() + " holds the session (" +
               std::to_string(refused_hellos_) + " refused so far)");
        return;
      }
      if (!gateway_) {
        log_("HELLO from " + d.from.text() + " (" + hello->gateway + "): streaming to it");
        last_reply_.reset();  // a new gateway numbers its commands from 1 again: no resend to answer
      }
      gateway_ = d.from;
      last_heard_ = Clock::now();
      if (!start_) start_ = last_heard_;  // the board's loop starts with the first subscription
      send_status();
      return;
    }
    if (!gateway_ || !(*gateway_ == d.from)) {
      log_("frame from " + d.from.text() + " ignored: no HELLO from it");
      return;
    }
    last_heard_ = Clock::now();
    if (const auto* excite = std::get_if<Excite>(&p)) send(reply(*excite));
  }

  ExciteReply reply(const Excite& x) {
    if (last_reply_ && last_reply_->command == x.command) return *last_reply_;  // a resend
    ExciteReply r{x.command, false, {}};
    if (!(x.amplitude <= o_.max_amplitude)) {
      r.reason = fit_text("amplitude " + std::to_string(x.amplitude) + " V above the board's amplifier limit " +
                          std::to_string(o_.max_amplitude) + " V");
    } else {
      const std::optional<Excite> before = excitation_;
      excitation_ = x;
      try {
        sim::build_scenario(current());  // what the loop cannot run is refused
        r.accepted = true;
      } catch (const Error& e) {
        excitation_ = before;
        r.reason = fit_text(e.what());
      }
    }
    log_("excitation command " + std::to_string(x.command) + " " + x.kind + " amplitude " +
         std::to_string(x.amplitude) + " V: " + (r.accepted ? "ACK" : "NACK " + r.reason));
    last_reply_ = r;
    return r;
  }

  EmulatorOptions o_;
  std::function<void(const std::string&)> log_;
  UdpSocket socket_;
  std::optional<Clock::time_point> start_;  // board time 0
  Clock::time_point last_heard_{}, last_status_{};
  std::optional<Endpoint> gateway_;
  std::optional<Excite> excitation_;
  std::optional<ExciteReply> last_reply_;
  std::uint32_t seq_ = 0, record_ = 0;
  std::uint64_t record_count_ = 0, refused_hellos_ = 0;
  double record_start_ = 0.0;  // board time of the current record's first sample
  bool fault_logged_ = false;
  Experiment record_data_;
  Eigen::Index row_ = 0;
};

}  // namespace

void validate(const EmulatorOptions& o) {
  if (!(o.speed > 0 && o.speed <= 100))
    throw Error("rig emulator: speed must be in (0, 100], got " + std::to_string(o.speed));
  if (!(o.max_amplitude >= 0))
    throw Error("rig emulator: max amplitude must be >= 0 V, got " + std::to_string(o.max_amplitude));
  if (!(o.lease > 0)) throw Error("rig emulator: lease must be > 0 s, got " + std::to_string(o.lease));
  if (!(o.fault_at >= 0)) throw Error("rig emulator: fault time must be >= 0 s, got " + std::to_string(o.fault_at));
  sim::build_scenario(o.scenario);
  if (o.fault) sim::build_scenario(*o.fault);
  if (o.fault && o.fault->plant != o.scenario.plant)  // the channels of one board do not change
    throw Error("rig emulator: the fault scenario's plant " + o.fault->plant + " is not the board's " +
                o.scenario.plant);
}

void run_emulator(const EmulatorOptions& options, const std::function<bool()>& running,
                  const std::function<void(const std::string&)>& log) {
  validate(options);
  Emulator(options, log).run(running);
}

}  // namespace ambid::rig
