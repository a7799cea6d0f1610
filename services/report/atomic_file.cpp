#include "services/report/atomic_file.hpp"

#include <fstream>
#include <random>
#include <system_error>

#include "core/error.hpp"

namespace ambid::report {

void write_file_atomically(const std::filesystem::path& path, std::string_view content) {
  namespace fs = std::filesystem;
  std::error_code error;
  const fs::path directory = path.parent_path();
  if (!directory.empty()) fs::create_directories(directory, error);
  if (error) throw Error("cannot create directory " + directory.string() + ": " + error.message());

  // A random suffix, so that two writers of the same file never share a temporary.
  std::random_device entropy;
  const fs::path temporary = path.parent_path() / ("." + path.filename().string() + ".tmp" + std::to_string(entropy()));
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    out.write(content.data(), static_cast<std::streamsize>(content.size()));
    out.close();
    if (!out) {
      fs::remove(temporary, error);
      throw Error("cannot write " + temporary.string());
    }
  }
  fs::rename(temporary, path, error);
  if (error) {
    std::error_code ignored;
    fs::remove(temporary, ignored);
    throw Error("cannot rename " + temporary.string() + " to " + path.string() + ": " + error.message());
  }
}

}  // namespace ambid::report
