#include "services/daemons/rig_source.hpp"

#include <cmath>
#include <deque>
#include <map>

#include "core/error.hpp"
#include "services/rig/rig_frame.hpp"
#include "services/rig/udp_endpoint.hpp"

namespace ambid::daemons {
namespace {

using Clock = std::chrono::steady_clock;
using namespace std::chrono_literals;

constexpr auto kHelloTimeout = 3s;  // > the emulator's 2 s lease: a lapsed session is taken over
constexpr auto kKeepAlivePeriod = 500ms;
// A frame this far behind the expected sequence number is a restarted rig, not a late frame.
constexpr std::uint32_t kRestartDistance = 1024;
constexpr int kDrainLimit = 1000;  // datagrams per next_rows call (about 45 ms of a 50x board)

double seconds(Clock::duration d) { return std::chrono::duration<double>(d).count(); }

std::string join(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ",") + n;
  return s;
}

class RigSource : public PlantSource {
 public:
  RigSource(const std::string& address, const SourceContext& c)
      : PlantSource(bus::SourceKind::rig, address),
        context_(c),
        rig_(rig::parse_endpoint(address)),
        socket_(rig::Endpoint{rig_.loopback() ? 0x7F000001u : 0u, 0}) {
    if (!context_.metrics) throw Error("rig source: no metrics given");
    Metrics& m = *context_.metrics;
    frames_ = &m.counter("ambid_rig_frames_received_total", "rig frames accepted", {});
    lost_ = &m.counter("ambid_rig_frames_lost_total", "rig frames missing from the sequence", {});
    hello();
    log("rig gateway " + socket_.local().text() + " -> " + rig_.text() + ": model " + status_.model + ", sample time " +
        std::to_string(status_.sample_time) + " s, y " + join(status_.y_names) + ", u " + join(status_.u_names) +
        ", r " + join(status_.r_names));
  }

  bool live() const override { return true; }

  std::optional<SourceRows> next_rows(std::chrono::milliseconds wait) override {
    const Clock::time_point end = Clock::now() + wait;
    // What has arrived, bounded so that a flood cannot starve the daemon's command handling.
    for (int k = 0; k < kDrainLimit; ++k) {
      auto d = socket_.receive(0ms);
      if (!d) break;
      process(*d);
    }
    while (ready_.empty() && Clock::now() < end) {
      keep_alive();
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(end - Clock::now());
      if (auto d = socket_.receive(std::max(left, 1ms))) process(*d);
    }
    keep_alive();
    check_silence();
    if (ready_.empty()) return std::nullopt;
    SourceRows rows = std::move(ready_.front());
    ready_.pop_front();
    return rows;
  }

  std::optional<SourceCondition> condition_change() override {
    std::optional<SourceCondition> c = std::move(condition_);
    condition_.reset();
    return c;
  }

  void excite(const ExcitationRequest& r) override {
    const rig::Excite command{++command_, r.kind, r.amplitude, r.f_min, r.f_max};
    const auto each = std::chrono::duration<double>(context_.rig.reply_timeout / 3);
    for (int attempt = 0; attempt < 3; ++attempt) {  // a lost command or reply is sent again
      send(command);
      const Clock::time_point end = Clock::now() + std::chrono::duration_cast<Clock::duration>(each);
      while (Clock::now() < end) {
        if (auto d = socket_.receive(5ms)) process(*d);
        const auto it = replies_.find(command.command);
        if (it == replies_.end()) continue;
        const rig::ExciteReply reply = it->second;
        replies_.erase(it);
        excitation_counter(reply.accepted ? "ack" : "nack").Increment();
        if (!reply.accepted) throw Error("rig " + rig_.text() + " NACK: " + reply.reason);
        return;
      }
    }
    excitation_counter("timeout").Increment();
    throw Error("rig " + rig_.text() + " did not answer excitation command " + std::to_string(command.command) +
                " within " + std::to_string(context_.rig.reply_timeout) + " s");
  }

 private:
  struct Pending {
    std::vector<double> t, y, u, r;
    bool starts_record = true;
    std::size_t size() const { return t.size(); }
  };

  void log(const std::string& line) const {
    if (context_.log) context_.log(line);
  }

  prometheus::Counter& excitation_counter(const std::string& result) {
    return context_.metrics->counter("ambid_rig_excitations_total", "excitation commands sent to the rig, by answer",
                                     {{"result", result}});
  }

  void send(const rig::Payload& p) {
    socket_.send_to(rig_, rig::encode(rig::Frame{seq_++, p}));
    last_sent_ = Clock::now();
  }

  // HELLO until the rig's STATUS comes back (every 250 ms, at most kHelloTimeout).
  void hello() {
    const Clock::time_point end = Clock::now() + kHelloTimeout;
    while (Clock::now() < end && !have_status_) {
      send(rig::Hello{"ambid plant gateway"});
      const Clock::time_point next = std::min(end, Clock::now() + 250ms);
      while (!have_status_ && Clock::now() < next)
        if (auto d = socket_.receive(10ms)) process(*d);
    }
    if (!have_status_)
      throw Error("rig " + rig_.text() + " did not answer HELLO within " + std::to_string(kHelloTimeout.count()) +
                  " s");
  }

  // KEEPALIVE while the rig streams; HELLO again while it is silent (it may have restarted).
  void keep_alive() {
    if (Clock::now() - last_sent_ < kKeepAlivePeriod) return;
    if (silent_)
      send(rig::Hello{"ambid plant gateway"});
    else
      send(rig::KeepAlive{});
  }

  void check_silence() {
    if (silent_ || seconds(Clock::now() - last_frame_) <= context_.rig.silence) return;
    silent_ = true;
    have_seq_ = false;  // the rig may come back restarted, counting from 0 again
    flush();
    condition_ = SourceCondition{
        false, "rig " + rig_.text() + " silent: no frame for " + std::to_string(context_.rig.silence) + " s"};
  }

  void reject(const std::string& reason, const std::string& detail) {
    prometheus::Counter& c = context_.metrics->counter("ambid_rig_frames_rejected_total",
                                                       "rig datagrams rejected, by reason", {{"reason", reason}});
    c.Increment();
    ++rejected_;
    // Every rejection is counted; the log gets the first ones and then every 1000th.
    if (rejected_ <= 20 || rejected_ % 1000 == 0)
      log("rig datagram rejected (" + reason + ", " + std::to_string(rejected_) + " so far): " + detail);
  }

  void process(const rig::UdpSocket::Datagram& d) {
    const rig::Decoded decoded = rig::decode(d.bytes);
    if (!decoded.frame)
      return reject(std::string(rig::fault_name(decoded.fault)), decoded.reason + " (from " + d.from.text() + ")");
    if (!(d.from == rig_)) return reject("sender", "a frame from " + d.from.text() + ", not the rig " + rig_.text());
    const rig::Payload& p = decoded.frame->payload;
    if (!std::holds_alternative<rig::RigStatus>(p) && !std::holds_alternative<rig::SampleBatch>(p) &&
        !std::holds_alternative<rig::ExciteReply>(p))
      return reject("direction", "a gateway frame from the rig");  // it neither counts nor keeps the rig alive
    if (!in_sequence(decoded.frame->seq)) return;
    frames_->Increment();
    last_frame_ = Clock::now();
    if (silent_) {
      silent_ = false;
      break_ = true;
      condition_ = SourceCondition{true, "rig " + rig_.text() + " streaming again"};
    }
    if (const auto* s = std::get_if<rig::RigStatus>(&p)) return take_status(*s);
    if (const auto* b = std::get_if<rig::SampleBatch>(&p)) return take_batch(*b);
    const auto& r = std::get<rig::ExciteReply>(p);
    replies_[r.command] = r;
  }

  // False for a late or repeated frame (dropped). A gap is counted and starts a new record.
  bool in_sequence(std::uint32_t seq) {
    if (have_seq_) {
      const std::uint32_t ahead = seq - next_seq_;
      if (ahead != 0 && ahead < 0x80000000u) {
        lost_->Increment(double(ahead));
        log("rig frames " + std::to_string(next_seq_) + ".." + std::to_string(seq - 1) + " lost: a new record starts");
        break_ = true;
      } else if (ahead != 0 && next_seq_ - seq <= kRestartDistance) {
        reject("sequence",
               "frame " + std::to_string(seq) + " late or repeated (expected " + std::to_string(next_seq_) + ")");
        return false;
      } else if (ahead != 0) {
        log("rig sequence restarted at " + std::to_string(seq) + ": a new record starts");
        break_ = true;
      }
    }
    have_seq_ = true;
    next_seq_ = seq + 1;
    return true;
  }

  void take_status(const rig::RigStatus& s) {
    if (have_status_ && (s.model != status_.model || s.y_names != status_.y_names || s.u_names != status_.u_names ||
                         s.r_names != status_.r_names || s.sample_time != status_.sample_time)) {
      log("rig " + rig_.text() + " changed its model or channels: a new record starts");
      flush();  // the pending rows belong to the old model and channels
      break_ = true;
    }
    if (have_status_ && s.state != status_.state)
      condition_ = SourceCondition{s.state == rig::RigState::running,
                                   "rig " + rig_.text() + " reports " +
                                       (s.state == rig::RigState::running ? "running" : "fault") + ": " + s.message};
    status_ = s;
    have_status_ = true;
  }

  void take_batch(const rig::SampleBatch& b) {
    if (!have_status_) return reject("mismatch", "samples before the rig's status");
    if (b.model != status_.model || std::size_t(b.ny) != status_.y_names.size() ||
        std::size_t(b.nu) != status_.u_names.size() || std::size_t(b.nr) != status_.r_names.size() ||
        std::abs(b.sample_time - status_.sample_time) > 0.01 * status_.sample_time)
      return reject("mismatch", "a batch of model " + b.model + " with " + std::to_string(b.ny) + "/" +
                                    std::to_string(b.nu) + "/" + std::to_string(b.nr) + " channels and sample time " +
                                    std::to_string(b.sample_time) + " s, the rig's status says " + status_.model +
                                    " with " + std::to_string(status_.sample_time) + " s");
    // Downstream the times are rebuilt from the first one: a clock jump must start a new record.
    const bool clock_jumps = !(std::abs(b.t[0] - next_t_) <= 0.01 * status_.sample_time);
    if (break_ || b.record != record_ || b.first_index != next_index_ || clock_jumps) {
      flush();
      pending_.starts_record = true;
    }
    break_ = false;
    record_ = b.record;
    next_index_ = b.first_index + b.count();
    next_t_ = b.t.back() + status_.sample_time;
    for (std::size_t k = 0; k < b.count(); ++k) {
      pending_.t.push_back(b.t[k]);
      pending_.y.insert(pending_.y.end(), b.y.begin() + std::ptrdiff_t(k * b.ny),
                        b.y.begin() + std::ptrdiff_t((k + 1) * b.ny));
      pending_.u.insert(pending_.u.end(), b.u.begin() + std::ptrdiff_t(k * b.nu),
                        b.u.begin() + std::ptrdiff_t((k + 1) * b.nu));
      pending_.r.insert(pending_.r.end(), b.r.begin() + std::ptrdiff_t(k * b.nr),
                        b.r.begin() + std::ptrdiff_t((k + 1) * b.nr));
      if (Eigen::Index(pending_.size()) >= context_.batch_samples) flush();
    }
  }

  // The pending rows as the next ready SourceRows; the following rows continue the record.
  void flush() {
    if (pending_.size() == 0) return;
    const Eigen::Index n = Eigen::Index(pending_.size());
    Experiment e;
    e.name = "rig " + rig_.text();
    e.sample_time = status_.sample_time;
    e.plant.model = status_.model;
    e.y_names = status_.y_names;
    e.u_names = status_.u_names;
    e.r_names = status_.r_names;
    e.t = Eigen::Map<const Eigen::VectorXd>(pending_.t.data(), n);
    e.y = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
        pending_.y.data(), n, Eigen::Index(e.y_names.size()));
    e.u = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
        pending_.u.data(), n, Eigen::Index(e.u_names.size()));
    e.r = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
        pending_.r.data(), n, Eigen::Index(e.r_names.size()));
    ready_.push_back(SourceRows{std::move(e), pending_.starts_record});
    pending_ = Pending{};
    pending_.starts_record = false;
  }

  SourceContext context_;
  rig::Endpoint rig_;
  rig::UdpSocket socket_;
  prometheus::Counter* frames_ = nullptr;
  prometheus::Counter* lost_ = nullptr;
  rig::RigStatus status_;
  bool have_status_ = false, have_seq_ = false, silent_ = false, break_ = true;
  std::uint32_t seq_ = 0, next_seq_ = 0, command_ = 0, record_ = 0;
  std::uint64_t next_index_ = 0, rejected_ = 0;
  double next_t_ = 0.0;  // the time the next sample of the record must have
  Clock::time_point last_sent_{}, last_frame_ = Clock::now();
  Pending pending_;
  std::deque<SourceRows> ready_;
  std::map<std::uint32_t, rig::ExciteReply> replies_;
  std::optional<SourceCondition> condition_;
};

}  // namespace

Experiment with_description(Experiment rows, Experiment description) {
  const auto names = [](const Experiment& e) {
    std::string s;
    for (const auto& n : e.signal_names()) s += (s.empty() ? "" : ", ") + n;
    return e.plant.model + " (" + s + ") at " + std::to_string(e.sample_time) + " s";
  };
  if (rows.plant.model != description.plant.model || rows.y_names != description.y_names ||
      rows.u_names != description.u_names || rows.r_names != description.r_names ||
      !(std::abs(rows.sample_time - description.sample_time) <= kSamplingTolerance * description.sample_time))
    throw Error("the rig sends " + names(rows) + " but its description (rig_description) has " + names(description));
  description.name = rows.name;
  description.t = std::move(rows.t);
  description.y = std::move(rows.y);
  description.u = std::move(rows.u);
  description.r = std::move(rows.r);
  return description;
}

std::unique_ptr<PlantSource> make_rig_source(const std::string& address, const SourceContext& context) {
  // Checked before a socket exists: nothing is sent off loopback unless the config allows it.
  if (!rig::parse_endpoint(address).loopback() && !context.rig.allow_remote)
    throw Error(
        "rig address " + address +
        " is not on loopback; set \"rig_allow_remote\": true in the plant config to reach a board on the network");
  return std::make_unique<RigSource>(address, context);
}

}  // namespace ambid::daemons
