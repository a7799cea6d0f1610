#pragma once
// Wakes the thread that waits on a bus when any of its endpoints receives data or a status
// event. Endpoints notify from middleware threads; the bus waits.
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>

namespace ambid::bus {

class Activity {
 public:
  void notify();
  // Returns the number of notifications so far, as soon as it differs from `seen` or when the
  // timeout has passed.
  std::uint64_t wait(std::uint64_t seen, std::chrono::milliseconds timeout);

 private:
  std::mutex mutex_;
  std::condition_variable changed_;
  std::uint64_t generation_ = 0;
};

}  // namespace ambid::bus
