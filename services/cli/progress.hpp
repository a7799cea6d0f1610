#pragma once
// Progress of a long offline run on stderr: "ambid diagnose: identify windows of run3.json
// 4/12, 2.1 s elapsed, about 4.2 s left", redrawn in place. Only when stderr is a terminal and
// the user did not ask for --quiet: pipes, logs and tests see nothing.
#include <chrono>
#include <cstddef>
#include <string>

namespace ambid::cli {

class Progress {
 public:
  Progress(std::string command, bool quiet);
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;
  ~Progress() { clear(); }

  // Item `done` of `total` of `stage` is finished (0 at the start of a stage). A new stage
  // restarts the estimate; the elapsed time counts from the first stage.
  void update(const std::string& stage, std::size_t done, std::size_t total);

  // Blanks the line (before printing results to the same terminal); update() draws it again.
  void clear();

  bool enabled() const { return enabled_; }

 private:
  using Clock = std::chrono::steady_clock;
  std::string command_, stage_;
  bool enabled_;
  Clock::time_point start_, stage_start_, last_draw_;
  std::size_t width_ = 0;  // of the line drawn last, to blank it
};

}  // namespace ambid::cli
