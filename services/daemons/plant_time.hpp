#pragma once
// The diagnostics daemon's clock of one plant, continuous across plant daemon restarts.
//
// Models arrive with the plant's time. A model at or before the last one processed is either
// a replay of the transient-local history (a late joiner or a reconnect sees the last models
// again: exactly the times of the newest few) or the first model of a restarted plant daemon,
// whose clock starts at 0 again (a time not among the newest few). A replay is skipped; a restart starts a new
// epoch placed one window after the last model, so the trend history continues at once instead
// of every model being discarded until the new clock passes the old maximum.
#include <deque>
#include <optional>

namespace ambid::daemons {

class PlantTime {
 public:
  struct Accepted {
    double time;         // on the continuous clock (the trend store's and the engine's)
    bool after_restart;  // the first model of a new epoch
  };
  // The continuous time of a model ending at `plant_time` that covers `window` seconds, or
  // nullopt when it was already seen.
  std::optional<Accepted> accept(double plant_time, double window);

  std::optional<double> last() const { return last_; }  // continuous time of the last accepted model

 private:
  std::optional<double> last_;
  double offset_ = 0.0;        // continuous time - plant time in the current epoch
  std::deque<double> recent_;  // plant times of the current epoch's last models, newest last
};

}  // namespace ambid::daemons
