#include "common/core/file_io.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <system_error>

namespace fleetmap {
namespace {

// Distinguishes the temporary files of concurrent calls within one process.
std::atomic<uint64_t> temp_file_counter{0};

Status WriteError(const std::string& path, int error) {
  // generic_category().message() is thread-safe, unlike strerror().
  return UnavailableError(path + ": cannot write: " + std::generic_category().message(error));
}

// Writes all of `contents` to `fd`, again after a signal or a short write. Returns 0 or an errno.
int WriteAll(int fd, std::string_view contents) {
  const char* data = contents.data();
  size_t left = contents.size();
  while (left > 0) {
    const ssize_t written = ::write(fd, data, left);
    if (written < 0) {
      if (errno == EINTR) continue;
      return errno;
    }
    if (written == 0) return EIO;  // no progress and no reason: do not spin
    data += written;
    left -= static_cast<size_t>(written);
  }
  return 0;
}

// Writes and closes `fd` (closed in every case). Returns 0 or the first errno. close() is
// checked because some file systems (NFS) report a failed write only there.
int WriteAndClose(int fd, std::string_view contents) {
  int error = WriteAll(fd, contents);
  if (::close(fd) != 0 && error == 0) error = errno;
  return error;
}

}  // namespace

Status WriteFileAtomically(const std::string& path, std::string_view contents) {
  struct stat existing;
  if (::lstat(path.c_str(), &existing) == 0 && !S_ISREG(existing.st_mode) &&
      !S_ISDIR(existing.st_mode)) {
    // A device, FIFO or symbolic link: write through it. A rename would replace the node itself:
    // as root, renaming over /dev/stdout would turn the device link into a regular file.
    const int fd = ::open(path.c_str(), O_WRONLY | O_TRUNC | O_CLOEXEC);
    if (fd < 0) return WriteError(path, errno);
    const int error = WriteAndClose(fd, contents);
    return error == 0 ? Status::Ok() : WriteError(path, error);
  }
  // A new file renamed over `path` (a directory at `path` too: rename() refuses to replace it).
  // No fsync: this guards against a killed process, not a power cut; SQLite keeps durable state.
  std::string temp;
  int fd = -1;
  do {
    temp = path + ".tmp." + std::to_string(::getpid()) + "." +
           std::to_string(temp_file_counter.fetch_add(1, std::memory_order_relaxed));
    fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
  } while (fd < 0 && errno == EEXIST);  // left behind by an earlier process with this pid
  if (fd < 0) return WriteError(path, errno);
  int error = WriteAndClose(fd, contents);
  if (error == 0 && ::rename(temp.c_str(), path.c_str()) != 0) error = errno;
  if (error != 0) {
    ::unlink(temp.c_str());
    return WriteError(path, error);
  }
  return Status::Ok();
}

Status WriteFileAtomically(const std::string& path, const std::vector<uint8_t>& contents) {
  return WriteFileAtomically(
      path, std::string_view(reinterpret_cast<const char*>(contents.data()), contents.size()));
}

}  // namespace fleetmap
