#pragma once
// Typed writers and readers. Each backend derives from Writer<M> / Reader<M> and reports its
// middleware status through the protected calls of Endpoint, so both vendors produce the same
// events. Status events queue up until events() collects them (at most max_events, oldest
// dropped first).
#include <atomic>
#include <cstddef>
#include <deque>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

#include "services/bus/activity.hpp"
#include "services/bus/validate.hpp"

namespace ambid::bus {

// matched / unmatched: a remote endpoint of this topic matched / went away.
// alive / liveliness_lost: on a reader, a matched writer asserted / lost its liveliness; on a
//   writer, liveliness_lost means it failed to assert its own.
// deadline_missed: an instance went longer than the profile's deadline without a sample.
enum class StatusKind { matched, unmatched, alive, liveliness_lost, deadline_missed };
std::string_view name(StatusKind kind);

struct StatusEvent {
  StatusKind kind;
  // matched, unmatched: endpoints matched now; alive, liveliness_lost on a reader: writers alive
  // now; liveliness_lost on a writer and deadline_missed: how often so far.
  int count;
  bool operator==(const StatusEvent&) const = default;
};

class Endpoint {
 public:
  static constexpr std::size_t max_events = 256;

  Endpoint(const Endpoint&) = delete;
  Endpoint& operator=(const Endpoint&) = delete;
  virtual ~Endpoint() = default;

  const std::string& topic() const { return topic_; }
  // Remote (or local) endpoints of the topic matched now.
  int matched() const { return matched_.load(); }
  // The status events since the last call, oldest first.
  std::vector<StatusEvent> events();

 protected:
  Endpoint(std::string topic, std::shared_ptr<Activity> activity);

  // Called by the backends, from middleware threads.
  void matched_changed(int current, int change);
  void liveliness_changed(int alive, int alive_change, int not_alive_change);
  void liveliness_lost(int total);
  void deadline_missed(int total);
  void data_available();

 private:
  void post(StatusEvent event);

  std::string topic_;
  std::shared_ptr<Activity> activity_;
  std::atomic<int> matched_{0};
  std::mutex mutex_;
  std::deque<StatusEvent> events_;
};

template <class Message>
class Writer : public Endpoint {
 public:
  // Throws InvalidMessage (nothing is sent) when the message breaks a bound, Error when the
  // middleware refuses it.
  void write(const Message& message) {
    validate(message);
    write_valid(message);
  }

 protected:
  using Endpoint::Endpoint;

 private:
  virtual void write_valid(const Message& message) = 0;
};

template <class Message>
class Reader : public Endpoint {
 public:
  // Every sample received since the last call, oldest first.
  virtual std::vector<Message> take() = 0;

 protected:
  using Endpoint::Endpoint;
};

}  // namespace ambid::bus
