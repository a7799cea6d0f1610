#include "core/format/file_lines.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <string>

#include "core/error.hpp"

namespace ambid {
namespace {

constexpr std::size_t kChunk = 1u << 16;

[[noreturn]] void fail(const std::string& what, const std::filesystem::path& path, int error) {
  throw Error("cannot " + what + " " + path.string() + ": " + std::strerror(error));
}

}  // namespace

FileLines::FileLines(const std::filesystem::path& path) : path_(path), buffer_(kChunk) {
  fd_ = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd_ < 0) fail("open", path, errno);
}

FileLines::~FileLines() { ::close(fd_); }

bool FileLines::fill() {
  if (at_end_) return false;
  if (begin_ > 0) {  // keep the unread bytes at the front
    std::memmove(buffer_.data(), buffer_.data() + begin_, end_ - begin_);
    end_ -= begin_;
    begin_ = 0;
  }
  if (end_ == buffer_.size()) {
    if (buffer_.size() > kMaxLineBytes)
      throw Error("line " + std::to_string(number_ + 1) + " is longer than " + std::to_string(kMaxLineBytes) +
                  " bytes; no experiment row is that long");
    buffer_.resize(std::min(2 * buffer_.size(), kMaxLineBytes + 2));  // + "\r\n"
  }
  for (;;) {
    const ssize_t n = ::read(fd_, buffer_.data() + end_, buffer_.size() - end_);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) fail("read", path_, errno);
    if (n == 0) at_end_ = true;
    end_ += std::size_t(n);
    return n > 0;
  }
}

std::optional<std::string_view> FileLines::next() {
  std::size_t searched = begin_;
  for (;;) {
    const char* newline = static_cast<const char*>(std::memchr(buffer_.data() + searched, '\n', end_ - searched));
    std::size_t line_end = newline ? std::size_t(newline - buffer_.data()) : end_;
    if (newline || (at_end_ && begin_ < end_)) {
      std::string_view line(buffer_.data() + begin_, line_end - begin_);
      begin_ = newline ? line_end + 1 : end_;
      ++number_;
      if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
      if (line.size() > kMaxLineBytes)
        throw Error("line " + std::to_string(number_) + " is longer than " + std::to_string(kMaxLineBytes) +
                    " bytes; no experiment row is that long");
      return line;
    }
    if (at_end_) return std::nullopt;
    const std::size_t unread = end_ - begin_;
    fill();
    searched = begin_ + unread;  // the bytes before were searched already
  }
}

}  // namespace ambid
