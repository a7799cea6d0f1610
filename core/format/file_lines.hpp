#pragma once
// The lines of a file read in chunks, so a reader holds one line at a time instead of the whole
// file (issue 18: a 2 GB experiment CSV read whole took 2.1 GB of memory before parsing).
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string_view>
#include <vector>

namespace ambid {

// A line longer than this is refused: no experiment row comes near it (16 channels of 25
// characters are 400 bytes), and the buffer stays bounded.
inline constexpr std::size_t kMaxLineBytes = 1u << 20;

class FileLines {
 public:
  // Throws Error naming the file when it cannot be opened.
  explicit FileLines(const std::filesystem::path& path);
  ~FileLines();
  FileLines(const FileLines&) = delete;
  FileLines& operator=(const FileLines&) = delete;

  // The next line without its '\n' or "\r\n" (valid until the next call), nullopt at the end.
  // Throws Error naming the file on a read error (a directory, an I/O error) and naming the
  // line when it is longer than kMaxLineBytes.
  std::optional<std::string_view> next();
  std::size_t number() const { return number_; }  // of the line last returned, from 1

 private:
  bool fill();  // reads more after the unread bytes; false at the end of the file

  std::filesystem::path path_;
  int fd_ = -1;
  std::vector<char> buffer_;
  std::size_t begin_ = 0, end_ = 0;  // the unread bytes
  std::size_t number_ = 0;
  bool at_end_ = false;
};

}  // namespace ambid
