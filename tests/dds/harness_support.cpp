#include "dds/harness.hpp"

#include <iterator>
#include <thread>

namespace ambid::bus::test {

bool eventually(const std::function<bool()>& done, std::chrono::milliseconds limit) {
  const auto end = std::chrono::steady_clock::now() + limit;
  while (!done()) {
    if (std::chrono::steady_clock::now() > end) return done();
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return true;
}

namespace harness_support {

template <class... Messages>
void write_each(AllWriters& writers, std::tuple<Messages...>*) {
  (
      [&] {
        for (const auto& m : round_trip_messages<Messages>()) writers.get<Messages>().write(m);
      }(),
      ...);
}

template <class... Messages>
void expect_each(AllReaders& readers, std::tuple<Messages...>*) {
  (
      [&] {
        const auto want = round_trip_messages<Messages>();
        const auto got = collect(readers.get<Messages>(), want.size());
        std::string missing;
        for (std::size_t i = 0; i < want.size(); ++i) {
          if (std::find(got.begin(), got.end(), want[i]) == got.end()) {
            missing += " " + std::to_string(i);
          }
        }
        EXPECT_TRUE(same_messages(got, want))
            << Topic<Messages>::name << ": received " << got.size() << " of " << want.size()
            << " messages; not received intact: sent message" << missing << " (0: small(1), 1: largest(), 2: small(2))";
      }(),
      ...);
}

}  // namespace harness_support
using namespace harness_support;

void write_all(AllWriters& writers) { write_each(writers, static_cast<AllMessages*>(nullptr)); }

void expect_all(AllReaders& readers) { expect_each(readers, static_cast<AllMessages*>(nullptr)); }

bool matched(const Endpoint& a, const Endpoint& b) { return a.matched() > 0 && b.matched() > 0; }

std::string pair_name(const testing::TestParamInfo<VendorPair>& info) {
  return std::string(info.param.writer) + "_to_" + info.param.reader;
}

void PrintTo(const VendorPair& pair, std::ostream* out) { *out << pair.writer << " -> " << pair.reader; }

int pair_index(const VendorPair& pair) {
  const auto* it = std::find_if(std::begin(vendor_pairs), std::end(vendor_pairs), [&](auto& p) {
    return std::string(p.writer) == pair.writer && std::string(p.reader) == pair.reader;
  });
  return static_cast<int>(it - std::begin(vendor_pairs));
}

bool EventLog::saw(StatusKind kind) {
  for (const StatusEvent& e : endpoint_.events()) seen_.push_back(e);
  return std::any_of(seen_.begin(), seen_.end(), [&](const StatusEvent& e) { return e.kind == kind; });
}

}  // namespace ambid::bus::test
