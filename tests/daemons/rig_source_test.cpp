// The rig gateway (plant source `rig`) in process against a scripted board on a loopback UDP
// socket: batches are cut at batch_samples; a sequence gap, a record change and a sample
// index jump each start a new record and a gap is counted as lost frames; batches that do
// not match the board's status are rejected; excitations wait for the ACK/NACK; silence and
// the return from it are reported once each.
#include "services/daemons/rig_source.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <thread>

#include "core/error.hpp"
#include "services/rig/rig_frame.hpp"
#include "services/rig/udp_endpoint.hpp"

namespace ambid::daemons {
namespace rig_source_test {

using ::testing::HasSubstr;
using namespace std::chrono_literals;

// The board side: answers the gateway's first HELLO with a status, then sends what the test says.
class ScriptedBoard {
 public:
  ScriptedBoard() : socket_(rig::parse_endpoint("127.0.0.1:0", true)) {}

  // Connects a gateway with `batch_samples` and the given silence; answers its HELLO.
  std::unique_ptr<PlantSource> connect(Eigen::Index batch_samples, double silence = 1.0) {
    std::thread answer([this] {
      for (int k = 0; k < 100 && !gateway_; ++k)
        if (auto d = socket_.receive(50ms); d && rig::decode(d->bytes).frame) gateway_ = d->from;
      if (gateway_) send(status());
    });
    SourceContext c;
    c.batch_samples = batch_samples;
    c.rig.silence = silence;
    c.metrics = &metrics;
    auto source = make_rig_source(socket_.local().text(), c);
    answer.join();
    return source;
  }

  static rig::RigStatus status() {
    rig::RigStatus s;
    s.sample_time = 1e-3;
    s.model = "test_model";
    s.y_names = {"y1", "y2"};
    s.u_names = {"u1"};
    s.r_names = {"r1"};
    return s;
  }

  // `count` samples of record `record` from `first`: t = first ms + t_offset, y = (k, -k, 10k...),
  // u = 2k, r = 3k.
  void batch(std::uint32_t record, std::uint64_t first, std::size_t count, std::uint8_t ny = 2, double t_offset = 0.0) {
    rig::SampleBatch b;
    b.record = record;
    b.first_index = first;
    b.sample_time = 1e-3;
    b.model = "test_model";
    b.ny = ny;
    b.nu = 1;
    b.nr = 1;
    for (std::size_t i = 0; i < count; ++i) {
      const double k = double(first + i);
      b.t.push_back(k * 1e-3 + t_offset);
      for (std::uint8_t j = 0; j < ny; ++j) b.y.push_back(j == 0 ? k : j == 1 ? -k : 10 * k);
      b.u.push_back(2 * k);
      b.r.push_back(3 * k);
    }
    send(b);
  }

  void send(const rig::Payload& p) { socket_.send_to(*gateway_, rig::encode(rig::Frame{seq_++, p})); }
  void skip_frame() { ++seq_; }
  rig::UdpSocket& socket() { return socket_; }
  double counter(const std::string& name, const prometheus::Labels& labels = {}) {
    return metrics.counter(name, "", labels).Value();
  }

  Metrics metrics{"plant", 0};

 private:
  rig::UdpSocket socket_;
  std::optional<rig::Endpoint> gateway_;
  std::uint32_t seq_ = 100;
};

std::vector<SourceRows> take(PlantSource& source, std::size_t n) {
  std::vector<SourceRows> rows;
  for (int k = 0; k < 100 && rows.size() < n; ++k)
    if (auto r = source.next_rows(20ms)) rows.push_back(std::move(*r));
  return rows;
}

// The samples waiting when the board announces other channels leave with the old ones; the
// new channels start a new record.
TEST(RigSource, ChangedChannelsFlushThePendingSamplesFirst) {
  ScriptedBoard board;
  auto source = board.connect(30);
  board.batch(0, 0, 10);  // pending: fewer than batch_samples
  rig::RigStatus wider = ScriptedBoard::status();
  wider.y_names = {"y1", "y2", "y3"};
  board.send(wider);
  board.batch(0, 10, 22, 3);
  board.batch(0, 32, 22, 3);
  const auto rows = take(*source, 2);
  ASSERT_EQ(rows.size(), 2u);
  ASSERT_EQ(rows[0].rows.samples(), 10);
  EXPECT_EQ(rows[0].rows.y.cols(), 2);
  EXPECT_EQ(rows[0].rows.y(9, 1), -9.0);
  EXPECT_TRUE(rows[1].starts_record);
  ASSERT_EQ(rows[1].rows.y.cols(), 3);
  EXPECT_EQ(rows[1].rows.y_names, wider.y_names);
  EXPECT_EQ(rows[1].rows.t(0), 10e-3);
  EXPECT_EQ(rows[1].rows.y(0, 2), 100.0);
}

// Times downstream are rebuilt from a record's first sample: a board clock that jumps while
// the sample index carries on starts a new record instead of being smoothed away.
TEST(RigSource, ClockJumpStartsANewRecord) {
  ScriptedBoard board;
  auto source = board.connect(30);
  board.batch(0, 0, 10);
  board.batch(0, 10, 22, 2, 0.5);  // same index sequence, clock 0.5 s ahead
  board.batch(0, 32, 22, 2, 0.5);
  const auto rows = take(*source, 2);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].rows.samples(), 10);
  EXPECT_TRUE(rows[1].starts_record);
  EXPECT_DOUBLE_EQ(rows[1].rows.t(0), 0.51);
}

TEST(RigSource, BatchesAreCutAndEveryBreakStartsANewRecord) {
  ScriptedBoard board;
  auto source = board.connect(30);
  EXPECT_TRUE(source->live());
  EXPECT_EQ(source->kind(), bus::SourceKind::rig);
  board.batch(0, 0, 22);
  board.batch(0, 22, 22);
  board.batch(0, 44, 22);  // 66 samples: 30 + 30 ready, 6 pending
  auto rows = take(*source, 2);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_TRUE(rows[0].starts_record);
  EXPECT_FALSE(rows[1].starts_record);
  ASSERT_EQ(rows[1].rows.samples(), 30);
  EXPECT_EQ(rows[1].rows.t(0), 30e-3);
  EXPECT_EQ(rows[1].rows.y(29, 1), -59.0);
  EXPECT_EQ(rows[1].rows.u(29, 0), 118.0);
  EXPECT_EQ(rows[1].rows.r(29, 0), 177.0);
  EXPECT_EQ(rows[1].rows.y_names, (std::vector<std::string>{"y1", "y2"}));
  EXPECT_EQ(rows[1].rows.plant.model, "test_model");

  board.skip_frame();  // a frame lost on the way: the 6 pending samples end the record
  board.batch(0, 66 + 22, 30);
  rows = take(*source, 2);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].rows.samples(), 6);
  EXPECT_FALSE(rows[0].starts_record);
  EXPECT_TRUE(rows[1].starts_record);
  EXPECT_EQ(rows[1].rows.t(0), 88e-3);
  EXPECT_EQ(board.counter("ambid_rig_frames_lost_total"), 1.0);

  board.batch(1, 0, 30);   // the board restarted its loop: record 1
  board.batch(1, 40, 30);  // samples 30..39 missing inside the record
  rows = take(*source, 2);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_TRUE(rows[0].starts_record);
  EXPECT_EQ(rows[0].rows.t(0), 0.0);
  EXPECT_TRUE(rows[1].starts_record);
  EXPECT_EQ(rows[1].rows.t(0), 40e-3);
  EXPECT_EQ(board.counter("ambid_rig_frames_lost_total"), 1.0);
  EXPECT_EQ(board.counter("ambid_rig_frames_received_total"), 7.0);  // status + 6 batches
}

TEST(RigSource, BatchesThatDoNotMatchTheStatusAreRejected) {
  ScriptedBoard board;
  auto source = board.connect(10);
  board.batch(0, 0, 10, 1);  // one y channel, the status names two
  board.batch(0, 0, 10);
  const auto rows = take(*source, 1);
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0].rows.y.cols(), 2);
  EXPECT_EQ(board.counter("ambid_rig_frames_rejected_total", {{"reason", "mismatch"}}), 1.0);
}

TEST(RigSource, ExcitationWaitsForTheBoardsAnswer) {
  ScriptedBoard board;
  auto source = board.connect(10);
  auto answer = [&](bool accepted, const std::string& reason) {
    return std::thread([&board, accepted, reason] {
      for (int k = 0; k < 100; ++k) {
        auto d = board.socket().receive(20ms);
        if (!d) continue;
        const auto f = rig::decode(d->bytes);
        if (!f.frame) continue;
        if (const auto* x = std::get_if<rig::Excite>(&f.frame->payload)) {
          EXPECT_EQ(x->kind, "multisine");
          EXPECT_EQ(x->amplitude, 0.2);
          EXPECT_EQ(x->f_max, 300.0);
          board.send(rig::ExciteReply{x->command, accepted, reason});
          return;
        }
      }
    });
  };
  std::thread ack = answer(true, "");
  EXPECT_NO_THROW(source->excite({"multisine", 0.2, 10.0, 300.0}));
  ack.join();
  std::thread nack = answer(false, "band above the board's 200 Hz");
  try {
    source->excite({"multisine", 0.2, 10.0, 300.0});
    ADD_FAILURE() << "a NACK must refuse the excitation";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("NACK: band above the board's 200 Hz"));
  }
  nack.join();
  // Nobody answers: refused after rig_reply_timeout (0.5 s), the command sent 3 times.
  try {
    source->excite({"prbs", 0.1, 0, 0});
    ADD_FAILURE() << "no answer must refuse the excitation";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("did not answer excitation command 3"));
  }
  std::size_t sent = 0;
  while (auto d = board.socket().receive(10ms)) {
    const auto f = rig::decode(d->bytes);
    sent += f.frame && std::holds_alternative<rig::Excite>(f.frame->payload);
  }
  EXPECT_EQ(sent, 3u);
  EXPECT_EQ(board.counter("ambid_rig_excitations_total", {{"result", "ack"}}), 1.0);
  EXPECT_EQ(board.counter("ambid_rig_excitations_total", {{"result", "nack"}}), 1.0);
  EXPECT_EQ(board.counter("ambid_rig_excitations_total", {{"result", "timeout"}}), 1.0);
}

TEST(RigSource, SilenceAndItsEndAreReportedOnce) {
  ScriptedBoard board;
  auto source = board.connect(10, 0.2);
  EXPECT_FALSE(source->condition_change());
  for (int k = 0; k < 20; ++k) source->next_rows(20ms);  // 0.4 s without a frame
  const auto silent = source->condition_change();
  ASSERT_TRUE(silent);
  EXPECT_FALSE(silent->ok);
  EXPECT_THAT(silent->message, HasSubstr("silent: no frame for 0.2"));
  EXPECT_FALSE(source->condition_change());
  board.batch(0, 500, 10);
  const auto rows = take(*source, 1);
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_TRUE(rows[0].starts_record);
  const auto back = source->condition_change();
  ASSERT_TRUE(back);
  EXPECT_TRUE(back->ok);
  EXPECT_THAT(back->message, HasSubstr("streaming again"));
}

TEST(RigSource, NoBoardNoSource) {
  rig::UdpSocket quiet(rig::parse_endpoint("127.0.0.1:0", true));  // bound, never answers
  Metrics metrics("plant", 0);
  SourceContext c;
  c.metrics = &metrics;
  try {
    make_rig_source(quiet.local().text(), c);
    ADD_FAILURE() << "a board that does not answer must be refused";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("did not answer HELLO within 3 s"));
  }
}

}  // namespace rig_source_test
}  // namespace ambid::daemons
