#pragma once
// Shared by the DDS tests: waiting with a deadline, collecting samples, comparing messages, the
// vendor pairs, and watching status events. Every test uses its own domain id (100..169).
#include <algorithm>
#include <chrono>
#include <functional>
#include <memory>
#include <string>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "dds/messages.hpp"
#include "services/bus/make_bus.hpp"
#include "services/bus/topics.hpp"

namespace ambid::bus::test {

// Generous: the test machine is shared and often loaded.
inline constexpr std::chrono::milliseconds patience{20000};

// Polls `done` every 10 ms until it holds or `limit` passes; returns done().
bool eventually(const std::function<bool()>& done, std::chrono::milliseconds limit = patience);

// What the reader receives until it has n samples or `limit` passes.
template <class Message>
std::vector<Message> collect(Reader<Message>& reader, std::size_t n, std::chrono::milliseconds limit = patience) {
  std::vector<Message> got;
  eventually(
      [&] {
        for (auto& m : reader.take()) got.push_back(std::move(m));
        return got.size() >= n;
      },
      limit);
  return got;
}

// Same messages in any order (readers may deliver different instances in any order).
template <class Message>
bool same_messages(const std::vector<Message>& got, const std::vector<Message>& want) {
  return got.size() == want.size() && std::is_permutation(got.begin(), got.end(), want.begin());
}

bool matched(const Endpoint& a, const Endpoint& b);

// The message types of a TypeList but Drop, as a std::tuple.
template <class Drop, class List>
struct TupleWithout;

template <class Drop, class... Messages>
struct TupleWithout<Drop, TypeList<Messages...>> {
  using type = decltype(std::tuple_cat(
      std::declval<std::conditional_t<std::is_same_v<Messages, Drop>, std::tuple<>, std::tuple<Messages>>>()...));
};

// Every message type on the bus (BusMessages, topics.hpp) but PlantDescription, which keeps only
// the latest sample per plant: the round trips of three samples per type do not apply to it
// (plant_description_test.cpp checks its topic).
using AllMessages = TupleWithout<PlantDescription, BusMessages>::type;

// One writer or one reader per message type of a tuple.
template <template <class> class Kind, class Messages>
class EndpointSet;

template <template <class> class Kind, class... Messages>
class EndpointSet<Kind, std::tuple<Messages...>> {
 public:
  explicit EndpointSet(Bus& bus) : endpoints_{make<Messages>(bus)...} {}

  template <class Message>
  Kind<Message>& get() {
    return *std::get<std::unique_ptr<Kind<Message>>>(endpoints_);
  }
  bool all_matched() const { return ((std::get<std::unique_ptr<Kind<Messages>>>(endpoints_)->matched() > 0) && ...); }

 private:
  template <class Message>
  static std::unique_ptr<Kind<Message>> make(Bus& bus) {
    if constexpr (std::is_same_v<Kind<Message>, Writer<Message>>) {
      return bus.writer<Message>();
    } else {
      return bus.reader<Message>();
    }
  }

  std::tuple<std::unique_ptr<Kind<Messages>>...> endpoints_;
};

using AllWriters = EndpointSet<Writer, AllMessages>;
using AllReaders = EndpointSet<Reader, AllMessages>;

// small(1), largest() and, where the history keeps more than one sample per instance, small(2)
// (same instance as small(1)).
template <class Message>
std::vector<Message> round_trip_messages() {
  std::vector<Message> messages{small<Message>(1), largest<Message>()};
  if (qos(Topic<Message>::profile).depth > 1) messages.push_back(small<Message>(2));
  return messages;
}
// Writes round_trip_messages() of every type.
void write_all(AllWriters& writers);
// Expects exactly round_trip_messages() of every type (gtest failures name the topic).
void expect_all(AllReaders& readers);

// Writer vendor -> reader vendor.
struct VendorPair {
  const char* writer;
  const char* reader;
};
inline const VendorPair vendor_pairs[] = {
    {"fastdds", "fastdds"}, {"cyclone", "cyclone"}, {"fastdds", "cyclone"}, {"cyclone", "fastdds"}};
std::string pair_name(const testing::TestParamInfo<VendorPair>& info);
void PrintTo(const VendorPair& pair, std::ostream* out);
// The index of the pair in vendor_pairs, to derive a domain id per pair.
int pair_index(const VendorPair& pair);

// Status events of one endpoint, kept as they are collected.
class EventLog {
 public:
  explicit EventLog(Endpoint& endpoint) : endpoint_(endpoint) {}
  // Collects new events; true when one of `kind` was seen so far.
  bool saw(StatusKind kind);
  const std::vector<StatusEvent>& seen() const { return seen_; }

 private:
  Endpoint& endpoint_;
  std::vector<StatusEvent> seen_;
};

}  // namespace ambid::bus::test
