// Issue 18, the soak: the stack as deployed (deploy/config: the bearing at 0.1 um / 1 mA in
// 10 s records, the identifier's rpem published every 0.5 s, the diagnostics' learning and
// persistence; plant, identifier, diagnostics daemons and a rig emulator, all real processes
// on their own domain) but the plant at 10x real time, for AMBID_SOAK_PLANT_SECONDS of plant
// time (default 3600: 6 minutes of wall time), with seeded random operator commands (source
// swaps between two simulations, a replayed recording and the rig; excitation changes within
// the limits), daemon kills and restarts (identifier, plant, rig emulator), a stalled
// diagnostics daemon, and garbage datagrams at the rig emulator and at the domain's DDS ports.
// Afterwards:
//   - no daemon ended that the test did not kill;
//   - no false alert: every WARN or ERROR is a history_gap (the bearing never changes);
//   - no hole in the stored R1 history without an alert that names it: a history_gap or
//     STALE alert at the hole's plant time, or an identifier's history_gap of the hole's length;
//   - the plant time is identified: of the history's span less the plant seconds the
//     history_gap alerts name (the documented gaps: a killed identifier, a stalled diagnostics
//     daemon, batches a restarted plant sent before anyone listened), the windows stored cover
//     at least kIdentifiedFraction; the rest is what is dropped by design (each record's 0.25 s
//     settle and its remainder shorter than a window, windows refused). With pem (until
//     2026-12-03) 305 windows, 152.5 s of 2758 s, were identified: pem fell behind at 10x;
//     with rpem 91 % (measured 2026-12-03; that run failed on 1339 false alerts, README).
// Run alone: ctest -R Soak (label slow).
#include <arpa/inet.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <mutex>
#include <random>
#include <set>
#include <thread>

#include <nlohmann/json.hpp>

#include "diagnostics/trend_store.hpp"
#include "services/bus/make_bus.hpp"
#include "services/convert/alert.hpp"
#include "stack_support.hpp"

namespace ambid::testing {
namespace soak_slow_test {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

constexpr int kDomain = 212;
constexpr int kRigPort = 19212;
constexpr double kSpeed = 10.0;
constexpr double kIdentifiedFraction = 0.8;
const std::string kRigAddress = "127.0.0.1:" + std::to_string(kRigPort);

double plant_seconds() {
  const char* text = std::getenv("AMBID_SOAK_PLANT_SECONDS");
  return text ? std::atof(text) : 3600.0;
}

void sleep_s(double seconds) { std::this_thread::sleep_for(std::chrono::duration<double>(seconds)); }

// Random bytes at a UDP port of 127.0.0.1; some start like an RTPS message.
class Garbage {
 public:
  explicit Garbage(std::mt19937_64& random) : random_(random), fd_(::socket(AF_INET, SOCK_DGRAM, 0)) {}
  ~Garbage() { ::close(fd_); }
  int sent() const { return sent_; }
  void send(int port) {
    std::string bytes(std::uniform_int_distribution<std::size_t>(0, 1400)(random_), '\0');
    for (char& c : bytes) c = char(std::uniform_int_distribution<int>(0, 255)(random_));
    if (bytes.size() >= 8 && random_() % 2) bytes.replace(0, 8, std::string("RTPS\x02\x02\x01\x0f", 8));
    sockaddr_in to{};
    to.sin_family = AF_INET;
    to.sin_port = htons(std::uint16_t(port));
    to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    sent_ += ::sendto(fd_, bytes.data(), bytes.size(), 0, reinterpret_cast<sockaddr*>(&to), sizeof to) >= 0;
  }

 private:
  std::mt19937_64& random_;
  int fd_;
  int sent_ = 0;
};

// Every alert of the run, as an operator's subscriber sees them: taken as they come, on a
// thread of its own (the reader keeps only the last 8 of each plant).
class AlertListener {
 public:
  AlertListener()
      : thread_([this] {
          auto bus = bus::make_bus("cyclone", kDomain);
          auto reader = bus->reader<bus::Alert>();
          while (listening_) {
            bus->wait(std::chrono::milliseconds(50));
            const std::lock_guard lock(mutex_);
            for (bus::Alert& a : reader->take()) alerts_.push_back(std::move(a));
          }
        }) {}
  ~AlertListener() { stop(); }
  std::vector<bus::Alert> stop() {
    listening_ = false;
    if (thread_.joinable()) thread_.join();
    return alerts_;
  }

 private:
  std::atomic<bool> listening_{true};
  std::mutex mutex_;
  std::vector<bus::Alert> alerts_;
  std::thread thread_;  // last: starts after the members it uses
};

TEST(Soak, TheStackSurvivesOperatorsKillsAndGarbageWithoutFalseAlertsOrSilentHoles) {
  const double duration = plant_seconds();
  std::mt19937_64 random(2026);
  const auto uniform = [&](double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(random); };
  Stack stack("soak", kDomain);
  // The stack as deployed (deploy/config: the bearing at 0.1 um / 1 mA with a 1 V PRBS in 10 s
  // records, the identifier's method and window, the diagnostics' learning and persistence),
  // but the plant at 10x real time.
  const fs::path deploy = fs::path(AMBID_SOURCE_DIR) / "deploy" / "config";
  const auto deployed = [&](const std::string& name) {
    return nlohmann::json::parse(std::ifstream(deploy / (name + ".json")));
  };
  nlohmann::json plant = deployed("plant");
  plant["target"] = (deploy / "nominal-bearing.json").string();
  plant["rig_description"] = (deploy / "rig-description.json").string();
  plant["speed"] = kSpeed;
  std::ofstream(stack.dir() / "plant.json") << plant.dump();
  const nlohmann::json identifier = deployed("identifier");
  std::ofstream(stack.dir() / "identifier.json") << identifier.dump();
  nlohmann::json diagnostics = deployed("diagnostics");
  diagnostics["store"] = stack.store().string();
  std::ofstream(stack.dir() / "diagnostics.json") << diagnostics.dump();
  const double window = identifier.at("window").get<double>();

  const std::string nominal = (deploy / "nominal-bearing.json").string();
  const std::string second = (stack.dir() / "nominal-seed-7.json").string();
  nlohmann::json seed7 = deployed("nominal-bearing");
  seed7["name"] = "nominal-seed-7";
  seed7["seed"] = 7;
  seed7["amplitude"] = 0.5;
  std::ofstream(second) << seed7.dump();
  const auto start_rig = [&] {
    stack.start_process("rig", {"rig-emulator", "--listen", kRigAddress, "--scenario", nominal, "--speed", "10"});
  };

  AlertListener listener;
  auto bus = bus::make_bus("cyclone", kDomain);
  auto excitations = bus->writer<bus::ExcitationCommand>();

  std::set<std::string> running{"diagnostics", "identifier", "plant", "rig"};
  for (const char* d : {"diagnostics", "identifier", "plant"}) stack.start(d);
  start_rig();
  const auto alive = [&](const std::string& when) {
    bool all = true;
    for (const std::string& d : running) {
      if (stack.running(d)) continue;
      ADD_FAILURE() << d << " ended " << when << ":\n" << stack.log(d);
      all = false;
    }
    return all;
  };

  sleep_s(3.0);
  const std::string replay = (stack.dir() / "recorded").string();
  // Long enough for windows after each pass's settling (0.25 s).
  const CommandResult recorded = stack.ambid("record --out " + replay + " --duration 3");
  ASSERT_EQ(recorded.status, 0) << recorded.output << stack.log("plant");

  Garbage garbage(random);
  const int dds_first_port = 7400 + 250 * kDomain;
  std::map<std::string, int> actions;
  std::uint64_t excitation_seq = 0;
  const auto end = Clock::now() + std::chrono::duration<double>(duration / kSpeed);
  while (Clock::now() < end) {
    for (int k = 0; k < 20; ++k) garbage.send(k % 2 ? kRigPort : dds_first_port + int(random() % 60));
    const int action = int(random() % 100);
    if (action < 30) {  // an operator swaps the source
      const std::string targets[] = {"sim " + nominal, "sim " + second, "replay " + replay, "rig " + kRigAddress};
      const std::string target = targets[random() % 4];
      const CommandResult r = stack.ambid("source set " + target);
      ++actions[r.status == 0 ? "swap " + target.substr(0, target.find(' ')) : "swap refused"];
    } else if (action < 55) {  // an excitation change within the limits
      bus::ExcitationCommand c;
      c.plant_id = "bearing-1";
      c.seq = ++excitation_seq;
      const std::string kinds[] = {"prbs", "multisine", "chirp"};
      c.kind = kinds[random() % 3];
      c.amplitude = uniform(0.05, 0.5);
      if (c.kind != "prbs") c.frequencies = {uniform(5, 50), uniform(100, 800)};
      excitations->write(c);
      ++actions["excite " + c.kind];
    } else if (action < 80) {  // a daemon killed and started again
      const std::string victims[] = {"identifier", "identifier", "plant", "plant", "rig"};
      const std::string victim = victims[random() % 5];
      stack.kill(victim);
      running.erase(victim);
      sleep_s(uniform(0.5, 4.0));
      if (victim == "rig")
        start_rig();
      else
        stack.start(victim);
      running.insert(victim);
      ++actions["kill " + victim];
    } else if (action < 90) {  // the diagnostics daemon stalls
      stack.pause("diagnostics");
      sleep_s(uniform(1.0, 3.0));
      stack.resume("diagnostics");
      ++actions["stall diagnostics"];
    } else {  // a burst of garbage
      for (int k = 0; k < 500; ++k) garbage.send(k % 2 ? kRigPort : dds_first_port + int(random() % 60));
      ++actions["garbage burst"];
    }
    if (!alive("during the soak")) break;
    sleep_s(uniform(2.0, 4.0));
  }
  sleep_s(3.0);
  const std::vector<bus::Alert> alerts = listener.stop();
  alive("at the end");
  for (const auto& [what, n] : actions) std::cout << "  " << what << ": " << n << "\n";
  std::cout << "  garbage datagrams: " << garbage.sent() << ", alerts: " << alerts.size() << "\n";

  // No false alert (the first few are shown).
  std::size_t gaps = 0, stale = 0, false_alerts = 0;
  std::map<std::string, int> false_by_parameter;
  for (const bus::Alert& a : alerts) {
    gaps += a.fault == "history_gap";
    stale += a.level == bus::AlertLevel::stale;
    if ((a.level != bus::AlertLevel::warn && a.level != bus::AlertLevel::error) || a.fault == "history_gap") continue;
    ++false_by_parameter[std::string(convert::level_name(a.level)) + " " + a.parameter];
    if (++false_alerts <= 10)
      ADD_FAILURE() << "false alert: " << convert::level_name(a.level) << " " << a.parameter << " " << a.fault << " at "
                    << a.time << ": " << a.message;
  }
  EXPECT_EQ(false_alerts, 0u);
  std::cout << "  history_gap alerts: " << gaps << ", STALE alerts: " << stale << ", false alerts:";
  for (const auto& [what, n] : false_by_parameter) std::cout << " " << what << " " << n;
  std::cout << "\n";

  // Every hole in the history named by an alert. Models come every window within a record and
  // 2 windows apart across records (the settle and the record's remainder): a hole is more than
  // 4 windows of plant time without one.
  const auto r1 = diag::TrendStore(stack.store(), diag::OpenMode::read_only).history("bearing-1", "R1");
  ASSERT_GE(r1.size(), 2u);
  std::size_t holes = 0;
  for (std::size_t k = 1; k < r1.size(); ++k) {
    const double from = r1[k - 1].time, to = r1[k].time;
    if (to - from <= 4 * window) continue;
    ++holes;
    bool named = false;
    for (const bus::Alert& a : alerts) {
      const bool at_hole = a.time >= from - 1.0 && a.time <= to + 1.0;
      const bool identifier_gap = a.parameter == "samples" && std::abs(a.value - (to - from)) < 2.0;
      named = named || ((a.fault == "history_gap" || a.level == bus::AlertLevel::stale) && at_hole) ||
              (a.fault == "history_gap" && identifier_gap);
    }
    EXPECT_TRUE(named) << "no alert names the hole from plant time " << from << " to " << to << " s";
  }
  // The account of the plant time: the span of the history (the store's clock runs on across
  // plant restarts, so a killed plant's downtime, when no samples existed, is not in it), the
  // part the history_gap alerts name (their value: plant seconds lost), and the part its
  // windows cover, which must be most of the rest.
  const double span = r1.back().time - r1.front().time + window;
  const double identified = double(r1.size()) * window;
  double alerted = 0.0;
  for (const bus::Alert& a : alerts) alerted += a.fault == "history_gap" ? a.value : 0.0;
  const double fraction = identified / (span - alerted);
  std::cout << "  plant time " << r1.back().time << " s, history span " << span << " s: " << r1.size()
            << " R1 windows of " << window << " s (" << identified << " s), history_gap alerts name " << alerted
            << " s, the rest " << span - identified - alerted << " s; identified " << 100.0 * fraction
            << " % of the plant time outside the alerted gaps; " << holes << " holes\n";
  EXPECT_GE(fraction, kIdentifiedFraction) << "plant time neither identified nor named by a gap alert";
}

}  // namespace soak_slow_test
}  // namespace ambid::testing
