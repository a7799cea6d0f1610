#pragma once
// A folder of its own per process for the fuzz targets' files, removed at exit.
#include <unistd.h>

#include <filesystem>
#include <string>
#include <system_error>

namespace ambid::fuzz {

class Scratch {
 public:
  explicit Scratch(const std::string& prefix)
      : dir_(std::filesystem::temp_directory_path() / (prefix + std::to_string(::getpid()))) {
    std::filesystem::create_directories(dir_);
  }
  ~Scratch() {
    std::error_code ignored;
    std::filesystem::remove_all(dir_, ignored);
  }
  Scratch(const Scratch&) = delete;
  Scratch& operator=(const Scratch&) = delete;
  std::filesystem::path file(const std::string& name) const { return dir_ / name; }

 private:
  std::filesystem::path dir_;
};

}  // namespace ambid::fuzz
