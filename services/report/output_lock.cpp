#include "services/report/output_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <system_error>

#include "core/error.hpp"

namespace ambid::report {

OutputLock::OutputLock(const std::filesystem::path& directory) {
  std::error_code error;
  std::filesystem::create_directories(directory, error);
  if (error) throw Error("cannot create directory " + directory.string() + ": " + error.message());
  const std::filesystem::path file = directory / ".ambid-lock";
  fd_ = ::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0) throw Error("cannot create the lock file " + file.string() + ": " + std::strerror(errno));
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    const int reason = errno;
    ::close(fd_);
    if (reason == EWOULDBLOCK)
      throw Error(directory.string() + " is being written by another ambid run (" + file.string() +
                  " is locked): wait for it to finish or choose another output directory");
    throw Error("cannot lock " + file.string() + ": " + std::strerror(reason));
  }
}

OutputLock::~OutputLock() { ::close(fd_); }  // closing releases the lock

}  // namespace ambid::report
