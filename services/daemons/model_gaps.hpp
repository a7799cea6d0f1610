#pragma once
// Models an identifier publishes are numbered 0, 1, 2, ... per identifier run (a window that
// cannot be identified takes no number). A consumer that fell behind or was stopped finds a
// jump forward: the models it never received, a hole in the trend history it must report.
#include <cstdint>
#include <optional>

namespace ambid::daemons {

class ModelGaps {
 public:
  // How many models were missed before the model numbered `seq`; a number at or below the last
  // one (a restarted identifier) starts the count again.
  std::uint64_t missed(std::uint64_t seq);
  // The last number given to missed() started the count again (not the first one seen).
  bool restarted() const { return restarted_; }

 private:
  std::optional<std::uint64_t> last_;
  bool restarted_ = false;
};

}  // namespace ambid::daemons
