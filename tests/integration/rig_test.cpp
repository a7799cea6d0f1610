// The plant daemon's rig source against the rig emulator, both real processes over loopback
// UDP (services/rig/RIG_PROTOCOL.md): samples of the emulated board reach the bus bit for bit,
// excitations within the limits reach the board (ACK, or its NACK reported), others are refused
// before they leave, a killed board is announced silent and picked up again when it returns,
// malformed datagrams are counted by reason and ignored, bad addresses are refused.
#include <arpa/inet.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <regex>
#include <sstream>
#include <thread>

#include "core/experiment_io.hpp"
#include "plant_sim/scenario.hpp"
#include "services/bus/make_bus.hpp"
#include "services/daemons/scenario_json.hpp"
#include "stack_support.hpp"

namespace ambid::testing {
namespace rig_test {

using ::testing::HasSubstr;
using ::testing::Not;
using namespace std::chrono_literals;

const std::string nominal = std::string(AMBID_SOURCE_DIR) + "/tests/integration/scenarios/quiet-bearing.json";

std::size_t count_of(const std::string& text, const std::string& needle) {
  std::size_t n = 0;
  for (auto at = text.find(needle); at != std::string::npos; at = text.find(needle, at + 1)) ++n;
  return n;
}

// True once the log of `name` holds `text` at least `times` times (a restarted process appends).
bool wait_for_log(const Stack& stack, const std::string& name, const std::string& text, std::chrono::seconds limit,
                  std::size_t times = 1) {
  const auto end = std::chrono::steady_clock::now() + limit;
  while (std::chrono::steady_clock::now() < end) {
    if (count_of(stack.log(name), text) >= times) return true;
    std::this_thread::sleep_for(50ms);
  }
  return false;
}

std::string address(int port) { return "127.0.0.1:" + std::to_string(port); }

// The plant daemon's log lines about rejected datagrams of the rig at `port`. Others do not
// count: the gateway's socket has an ephemeral port, which the domain's RTPS traffic can reach
// too (a port a participant used before), and those datagrams are rejected "(from ADDRESS)" of
// their sender or as "not the rig".
std::vector<std::string> rig_rejections(const std::string& log, int port) {
  std::vector<std::string> found;
  std::istringstream lines(log);
  for (std::string line; std::getline(lines, line);) {
    if (line.find("rejected") == std::string::npos || line.find("not the rig") != std::string::npos) continue;
    const auto from = line.rfind("(from ");
    if (from == std::string::npos || line.compare(from, std::string::npos, "(from " + address(port) + ")") == 0)
      found.push_back(line);
  }
  return found;
}

void start_emulator(Stack& stack, int port, const std::vector<std::string>& extra = {}) {
  std::vector<std::string> args{"rig-emulator", "--listen", address(port), "--scenario", nominal, "--speed", "10"};
  args.insert(args.end(), extra.begin(), extra.end());
  const std::size_t before = count_of(stack.log("rig"), "listening on ");
  stack.start_process("rig", args);
  ASSERT_TRUE(wait_for_log(stack, "rig", "listening on " + address(port), 10s, before + 1)) << stack.log("rig");
}

void swap_to_rig(Stack& stack, int port) {
  const CommandResult swap = stack.ambid("source set rig " + address(port));
  ASSERT_EQ(swap.status, 0) << swap.output << stack.log("plant");
  EXPECT_THAT(swap.output, HasSubstr("source rig " + address(port) + " (source swapped"));
}

// The value of the Prometheus sample `name{...labels...}` whose labels contain `label`.
double metric(const std::string& body, const std::string& name, const std::string& label) {
  std::istringstream lines(body);
  for (std::string line; std::getline(lines, line);)
    if (line.rfind(name + "{", 0) == 0 && line.find(label) != std::string::npos)
      return std::stod(line.substr(line.rfind(' ') + 1));
  return -1.0;
}

TEST(Rig, SamplesOfTheBoardReachTheBusBitForBit) {
  Stack stack("rig_samples", 180);
  stack.start("plant", {"--metrics-port", "19280"});
  start_emulator(stack, 19180);
  swap_to_rig(stack, 19180);
  EXPECT_THAT(stack.ambid("status --wait 2").output, HasSubstr("source rig 127.0.0.1:19180"));
  const std::string stem = (stack.dir() / "recorded").string();
  const CommandResult r = stack.ambid("record --out " + stem + " --duration 0.5");
  ASSERT_EQ(r.status, 0) << r.output << stack.log("plant");
  const Experiment e = read_experiment(stem).experiment;
  ASSERT_EQ(e.samples(), 5000);
  // The board runs the nominal scenario record after record, record k with seed 1 + k, and
  // the window lies inside one record: find it in an independent simulation, compare exactly.
  sim::ScenarioOptions o = daemons::read_scenario_file(nominal);
  bool found = false;
  for (std::uint64_t k = 0; k < 400 && !found; ++k) {
    o.seed = 1 + k;
    const Experiment truth = sim::simulate_scenario(o);
    // Every record starts at the operating point: only the whole window identifies it.
    for (Eigen::Index i = 0; i + e.samples() <= truth.samples() && !found; ++i)
      found = truth.y.row(i) == e.y.row(0) && truth.y.middleRows(i, e.samples()) == e.y &&
              truth.u.middleRows(i, e.samples()) == e.u && truth.r.middleRows(i, e.samples()) == e.r;
  }
  EXPECT_TRUE(found) << "the recorded window is not, bit for bit, a window of the board's records";
  const std::string m = http_get(19280, "/metrics");
  EXPECT_GT(metric(m, "ambid_rig_frames_received_total", "role=\"plant\""), 200.0) << m;
  EXPECT_THAT(m, Not(HasSubstr("ambid_rig_frames_rejected_total{")));
  EXPECT_THAT(stack.log("plant"), HasSubstr("rig gateway 127.0.0.1:"));
}

class Excitations {
 public:
  Excitations(Stack& stack, int domain)
      : stack_(stack), bus_(bus::make_bus("cyclone", domain)), writer_(bus_->writer<bus::ExcitationCommand>()) {}
  // Sends the command until the plant logs its outcome (a volatile command written before
  // the plant's reader matched us is lost); returns that log line.
  std::string send(std::uint64_t seq, const std::string& kind, double amplitude, std::vector<double> frequencies = {}) {
    bus::ExcitationCommand c;
    c.plant_id = "bearing-1";
    c.seq = seq;
    c.kind = kind;
    c.amplitude = amplitude;
    c.frequencies = std::move(frequencies);
    const std::regex outcome("[^\n]*(\\(command " + std::to_string(seq) + "\\)|command " + std::to_string(seq) +
                             " refused)[^\n]*");
    for (int attempt = 0; attempt < 10; ++attempt) {
      for (int k = 0; k < 200 && writer_->matched() == 0; ++k) bus_->wait(50ms);
      writer_->write(c);
      for (int k = 0; k < 30; ++k) {
        std::smatch match;
        const std::string log = stack_.log("plant");
        if (std::regex_search(log, match, outcome)) return match.str();
        std::this_thread::sleep_for(100ms);
      }
    }
    return "no outcome";
  }

 private:
  Stack& stack_;
  std::unique_ptr<bus::Bus> bus_;
  std::unique_ptr<bus::Writer<bus::ExcitationCommand>> writer_;
};

TEST(Rig, ExcitationsWithinLimitsReachTheBoardOthersAreRefusedBeforeTheyLeave) {
  Stack stack("rig_excitation", 181);  // plant limits: 0.5 V, 2000 Hz (the defaults)
  stack.start("plant");
  start_emulator(stack, 19181, {"--max-amplitude", "0.2"});
  swap_to_rig(stack, 19181);
  Excitations excite(stack, 181);
  EXPECT_THAT(excite.send(1, "prbs", 0.1), HasSubstr("excitation prbs accepted (command 1)"));
  EXPECT_THAT(
      excite.send(2, "multisine", 0.3, {10, 100}),
      HasSubstr(
          "refused: rig 127.0.0.1:19181 NACK: amplitude 0.300000 V above the board's amplifier limit 0.200000 V"));
  EXPECT_THAT(excite.send(3, "prbs", 0.8), HasSubstr("refused: amplitude 0.800000 V outside 0..0.500000 V"));
  EXPECT_THAT(excite.send(4, "multisine", 0.1, {5000}),
              HasSubstr("refused: frequency 5000.000000 Hz outside (0, 2000"));
  // Only the two within the plant's limits reached the board.
  const std::string board = stack.log("rig");
  EXPECT_EQ(count_of(board, "excitation command "), 2u) << board;
  EXPECT_THAT(board, HasSubstr("prbs amplitude 0.100000 V: ACK"));
  EXPECT_THAT(board, HasSubstr("multisine amplitude 0.300000 V: NACK"));
  // The accepted PRBS of 0.1 V runs on the board: the recorded excitation is +-0.1 V.
  std::this_thread::sleep_for(1s);  // 10 s of board time: the records after the ACK
  const std::string stem = (stack.dir() / "excited").string();
  ASSERT_EQ(stack.ambid("record --out " + stem + " --duration 0.3").status, 0);
  const Experiment e = read_experiment(stem).experiment;
  EXPECT_NEAR(e.r.cwiseAbs().maxCoeff(), 0.1, 1e-12);
  EXPECT_NEAR(e.r.cwiseAbs().minCoeff(), 0.1, 1e-12);
  // Swapped away, the gateway stops its keep-alives and the board its stream (2 s lease).
  ASSERT_EQ(stack.ambid("source set sim " + nominal).status, 0);
  EXPECT_TRUE(wait_for_log(stack, "rig", "silent for 2.000000 s: streaming stopped", 5s)) << stack.log("rig");
}

TEST(Rig, KilledBoardIsAnnouncedSilentAndPickedUpWhenItReturns) {
  Stack stack("rig_silent", 182);
  stack.start("plant");
  start_emulator(stack, 19182);
  swap_to_rig(stack, 19182);
  stack.kill("rig");
  ASSERT_TRUE(wait_for_log(stack, "plant", "rig 127.0.0.1:19182 silent: no frame for 1.0", 5s)) << stack.log("plant");
  const CommandResult status = stack.ambid("status --wait 2");
  EXPECT_THAT(status.output, HasSubstr("source rig 127.0.0.1:19182"));
  EXPECT_THAT(status.output, HasSubstr("(rig 127.0.0.1:19182 silent: no frame for 1.0"));
  EXPECT_THAT(status.output, HasSubstr("WARN rig 127.0.0.1:19182 silent"));  // the plant's Health
  start_emulator(stack, 19182);
  ASSERT_TRUE(wait_for_log(stack, "plant", "rig 127.0.0.1:19182 streaming again", 5s)) << stack.log("plant");
  // The restarted board counts from 0: accepted.
  EXPECT_THAT(rig_rejections(stack.log("plant"), 19182), ::testing::IsEmpty()) << stack.log("plant");
  const CommandResult r = stack.ambid("record --out " + (stack.dir() / "again").string() + " --duration 0.2");
  EXPECT_EQ(r.status, 0) << r.output;
}

// An independent bitwise CRC-32 (IEEE), to build frames by hand.
std::uint32_t crc32(const std::vector<std::uint8_t>& b) {
  std::uint32_t c = 0xFFFFFFFFu;
  for (std::uint8_t v : b) {
    c ^= v;
    for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xEDB88320u & (0u - (c & 1u)));
  }
  return ~c;
}

// A 20-byte header-only frame (KEEPALIVE is type 2), sealed with its CRC unless `bad_crc`.
std::vector<std::uint8_t> header(std::uint16_t version, std::uint32_t length, bool bad_crc = false) {
  std::vector<std::uint8_t> b{'A', 'M', 'B', 'R', std::uint8_t(version), 0, 2, 0};
  for (int k = 0; k < 4; ++k) b.push_back(std::uint8_t(length >> (8 * k)));
  for (int k = 0; k < 8; ++k) b.push_back(0);  // seq 0, CRC 0
  const std::uint32_t c = crc32(b) ^ (bad_crc ? 1u : 0u);
  for (int k = 0; k < 4; ++k) b[16 + std::size_t(k)] = std::uint8_t(c >> (8 * k));
  return b;
}

TEST(Rig, MalformedDatagramsAreCountedByReasonAndIgnored) {
  Stack stack("rig_malformed", 183);
  stack.start("plant", {"--metrics-port", "19283"});
  start_emulator(stack, 19183);
  swap_to_rig(stack, 19183);
  std::smatch gateway;
  const std::string log = stack.log("plant");
  ASSERT_TRUE(std::regex_search(log, gateway, std::regex("rig gateway 127\\.0\\.0\\.1:([0-9]+) ->"))) << log;
  const int fd = socket(AF_INET, SOCK_DGRAM, 0);
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_port = htons(std::uint16_t(std::stoi(gateway[1])));
  to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  const std::vector<std::vector<std::uint8_t>> datagrams{
      {'h', 'e', 'l', 'l', 'o'},           // short
      std::vector<std::uint8_t>(2000, 0),  // oversize
      std::vector<std::uint8_t>(20, 'X'),  // magic
      header(2, 20),                       // version
      header(1, 24),                       // length
      header(1, 20, true),                 // crc
      header(1, 20)};                      // a valid KEEPALIVE, but not from the rig: sender
  for (const auto& d : datagrams)
    ASSERT_EQ(sendto(fd, d.data(), d.size(), 0, reinterpret_cast<const sockaddr*>(&to), sizeof to), ssize_t(d.size()));
  close(fd);
  std::this_thread::sleep_for(500ms);
  const std::string m = http_get(19283, "/metrics");
  for (const char* reason : {"short", "oversize", "magic", "version", "length", "crc", "sender"})
    EXPECT_EQ(metric(m, "ambid_rig_frames_rejected_total", std::string("reason=\"") + reason + "\""), 1.0)
        << reason << "\n"
        << m;
  EXPECT_THAT(stack.log("plant"), HasSubstr("rig datagram rejected (crc"));
  // The stream goes on.
  const CommandResult r = stack.ambid("record --out " + (stack.dir() / "after").string() + " --duration 0.2");
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_THAT(stack.ambid("status --wait 2").output, HasSubstr("source rig 127.0.0.1:19183"));
}

TEST(Rig, BadRigAddressesAreRefusedAndThePlantKeepsItsSource) {
  Stack stack("rig_refusal", 184);
  stack.start("plant");
  const std::vector<std::pair<std::string, std::string>> cases{
      {"localhost:19184", "'localhost' is not a numeric IPv4 address"},
      {"127.0.0.1", "expected A.B.C.D:PORT"},
      {"127.0.0.1:99999", "port 99999 outside 1..65535"},
      {"192.0.2.1:19184", "is not on loopback; set \"rig_allow_remote\": true"},
      {"127.0.0.1:19184", "rig 127.0.0.1:19184 did not answer HELLO within 3 s"}};  // nobody listens
  for (const auto& [target, why] : cases) {
    const CommandResult r = stack.ambid("source set rig " + target);
    EXPECT_EQ(r.status, 1) << r.output;
    EXPECT_THAT(r.output, HasSubstr("refused the source: "));
    EXPECT_THAT(r.output, HasSubstr(why));
  }
  const CommandResult status = stack.ambid("status --wait 2");
  EXPECT_THAT(status.output, HasSubstr("source sim "));
  EXPECT_THAT(status.output, HasSubstr("rejected 5"));
}

TEST(Rig, EmulatorRefusesBadOptionsNamingThem) {
  const std::vector<std::pair<std::string, std::string>> cases{
      {"--listen 10.0.0.1:19186", "--listen 10.0.0.1:19186 is not a loopback address"},
      {"--listen localhost:19186", "'localhost' is not a numeric IPv4 address"},
      {"--listen 127.0.0.1:19186 --speed 0", "speed must be in (0, 100], got 0"},
      {"--listen 127.0.0.1:19186 --max-amplitude -1", "max amplitude must be >= 0 V"}};
  for (const auto& [args, why] : cases) {
    const CommandResult r = run_ambid("rig-emulator " + args);
    EXPECT_EQ(r.status, 1) << args << ": " << r.output;
    EXPECT_THAT(r.output, HasSubstr(why)) << args;
  }
}

}  // namespace rig_test
}  // namespace ambid::testing
