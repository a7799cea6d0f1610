#pragma once
// Writes a whole file so that readers see either the old content or the new, never a part:
// the text goes to a temporary file in the same directory, which is then renamed over the target.
#include <filesystem>
#include <string_view>

namespace ambid::report {

// Creates missing parent directories. Throws ambid::Error naming the path on any failure.
void write_file_atomically(const std::filesystem::path& path, std::string_view content);

}  // namespace ambid::report
