#include "services/cli/progress.hpp"

#include <unistd.h>

#include <cstdio>
#include <iostream>

namespace ambid::cli {
namespace {

constexpr auto kRedraw = std::chrono::milliseconds(100);  // at most ten lines a second

std::string seconds(double s) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f s", s);
  return text;
}

}  // namespace

Progress::Progress(std::string command, bool quiet)
    : command_(std::move(command)),
      enabled_(!quiet && ::isatty(STDERR_FILENO) == 1),
      start_(Clock::now()),
      stage_start_(start_),
      last_draw_() {}

void Progress::clear() {
  if (enabled_ && width_ > 0) std::cerr << '\r' << std::string(width_, ' ') << '\r' << std::flush;
  width_ = 0;
}

void Progress::update(const std::string& stage, std::size_t done, std::size_t total) {
  if (!enabled_) return;
  const Clock::time_point now = Clock::now();
  if (stage != stage_) {
    stage_ = stage;
    stage_start_ = now;
  } else if (now - last_draw_ < kRedraw && done < total) {
    return;
  }
  last_draw_ = now;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double in_stage = std::chrono::duration<double>(now - stage_start_).count();
  std::string line = command_ + ": " + stage + " " + std::to_string(done) + "/" + std::to_string(total) + ", " +
                     seconds(elapsed) + " elapsed";
  // The items of a stage take about equally long (windows of one length, rows of one file).
  if (done > 0 && done < total) line += ", about " + seconds(in_stage / double(done) * double(total - done)) + " left";
  const std::size_t width = line.size();
  if (line.size() < width_) line += std::string(width_ - line.size(), ' ');
  width_ = width;
  std::cerr << '\r' << line << std::flush;
}

}  // namespace ambid::cli
