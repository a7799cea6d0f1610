#include "core/experiment_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <random>
#include <set>
#include <utility>

#include "core/error.hpp"

namespace ambid {
namespace {

[[noreturn]] void fail(const std::string& what, const std::filesystem::path& path, int error) {
  throw Error("cannot " + what + " " + path.string() + ": " + std::strerror(error));
}

// Closes the descriptor on every path out, including exceptions.
class Descriptor {
 public:
  explicit Descriptor(int fd) : fd_(fd) {}
  Descriptor(const Descriptor&) = delete;
  Descriptor& operator=(const Descriptor&) = delete;
  ~Descriptor() {
    if (fd_ >= 0) ::close(fd_);
  }
  int get() const { return fd_; }
  int release() { return std::exchange(fd_, -1); }

 private:
  int fd_;
};

std::filesystem::path temporary_beside(const std::filesystem::path& target) {
  static thread_local std::mt19937_64 random{std::random_device{}()};
  char suffix[17];
  std::snprintf(suffix, sizeof suffix, "%016llx", static_cast<unsigned long long>(random()));
  return target.parent_path() / ("." + target.filename().string() + ".tmp-" + suffix);
}

void write_all(const std::filesystem::path& path, const std::string& content) {
  Descriptor fd(::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666));
  if (fd.get() < 0) fail("create", path, errno);
  std::size_t done = 0;
  while (done < content.size()) {
    const ssize_t n = ::write(fd.get(), content.data() + done, content.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) fail("write", path, errno);
    done += static_cast<std::size_t>(n);
  }
  if (::fsync(fd.get()) != 0) fail("flush", path, errno);
  if (::close(fd.release()) != 0) fail("close", path, errno);
}

// Makes the renames themselves durable; best effort, some file systems refuse it.
void sync_directory(const std::filesystem::path& dir) {
  Descriptor fd(::open(dir.empty() ? "." : dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC));
  if (fd.get() >= 0) ::fsync(fd.get());
}

}  // namespace

std::string read_text_file(const std::filesystem::path& path) {
  Descriptor fd(::open(path.c_str(), O_RDONLY | O_CLOEXEC));
  if (fd.get() < 0) fail("open", path, errno);
  std::string content;
  char buffer[1 << 16];
  for (;;) {
    const ssize_t n = ::read(fd.get(), buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) fail("read", path, errno);
    if (n == 0) return content;
    content.append(buffer, static_cast<std::size_t>(n));
  }
}

void write_files_atomically(const std::vector<std::pair<std::filesystem::path, std::string>>& files) {
  // Every new content goes to a temporary and every existing target gets a second name (a hard
  // link, its backup) before the first rename: a target that cannot be replaced (a directory in
  // its place) fails before anything changed, and a rename that fails later puts the targets
  // renamed before it back from their backups, so a failed set leaves every target as it was.
  // (A file system without hard links replaces such a target without a backup: a later failure
  // then leaves it new.)
  enum class Before { absent, backed_up, unsaved };
  std::vector<std::filesystem::path> temporaries, backups(files.size());
  std::vector<Before> before(files.size(), Before::absent);
  std::size_t renamed = 0;
  auto roll_back = [&] {
    for (std::size_t i = 0; i < files.size(); ++i) {
      const bool replaced = i < renamed;
      if (before[i] == Before::backed_up && replaced) ::rename(backups[i].c_str(), files[i].first.c_str());
      if (before[i] == Before::backed_up && !replaced) ::unlink(backups[i].c_str());
      if (before[i] == Before::absent && replaced) ::unlink(files[i].first.c_str());
    }
    for (const auto& t : temporaries) ::unlink(t.c_str());  // a temporary already renamed is gone
  };
  try {
    for (const auto& [target, content] : files) {
      temporaries.push_back(temporary_beside(target));
      write_all(temporaries.back(), content);
    }
    for (std::size_t i = 0; i < files.size(); ++i) {
      const std::filesystem::path& target = files[i].first;
      backups[i] = temporary_beside(target);
      if (::link(target.c_str(), backups[i].c_str()) == 0) {
        before[i] = Before::backed_up;
        continue;
      }
      if (errno == ENOENT) continue;
      std::error_code ignored;
      if (std::filesystem::is_directory(target, ignored)) fail("replace", target, EISDIR);
      before[i] = Before::unsaved;
    }
    for (; renamed < files.size(); ++renamed)
      if (::rename(temporaries[renamed].c_str(), files[renamed].first.c_str()) != 0)
        fail("replace", files[renamed].first, errno);
  } catch (...) {
    roll_back();
    throw;
  }
  for (std::size_t i = 0; i < files.size(); ++i)
    if (before[i] == Before::backed_up) ::unlink(backups[i].c_str());
  std::set<std::filesystem::path> directories;
  for (const auto& file : files) directories.insert(file.first.parent_path());
  for (const auto& dir : directories) sync_directory(dir);
}

}  // namespace ambid
