#pragma once
// One writer per output directory: `ambid diagnose`, `audit` and `frf` hold an exclusive
// advisory lock (flock) on DIR/.ambid-lock for the whole run, so two runs into one folder
// cannot interleave their files or their trend store. The kernel drops the lock when the
// process ends, however it ends; the empty lock file stays.
#include <filesystem>

namespace ambid::report {

class OutputLock {
 public:
  // Creates `directory` when missing. Throws Error naming the directory when another process
  // holds its lock, or when the lock file cannot be created.
  explicit OutputLock(const std::filesystem::path& directory);
  ~OutputLock();
  OutputLock(const OutputLock&) = delete;
  OutputLock& operator=(const OutputLock&) = delete;

 private:
  int fd_ = -1;
};

}  // namespace ambid::report
