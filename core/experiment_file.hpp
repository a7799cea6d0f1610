#pragma once
// Whole-file reads and crash-safe writes for experiment files.
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace ambid {

// The bytes of `path`. Throws Error naming the file and the system's reason.
std::string read_text_file(const std::filesystem::path& path);

// Writes each (path, content) to a fresh temporary file beside its target, flushes it to disk,
// and only when all are written renames them into place. An error leaves every target as it
// was (a rename that fails puts the targets renamed before it back); a crash leaves every
// target either untouched or complete, never half written (the set as a whole is not atomic
// against a crash between two renames: the first file new, the second old).
void write_files_atomically(const std::vector<std::pair<std::filesystem::path, std::string>>& files);

}  // namespace ambid
