#include "common/store/store_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <thread>

namespace fleetmap::store {
namespace {

// How often a waiting Acquire tries again.
constexpr std::chrono::milliseconds kRetryPeriod{100};

std::string Holder(pid_t pid) {
  return pid > 0 ? "process " + std::to_string(pid) : "a process that has not written its pid yet";
}

std::string Seconds(std::chrono::milliseconds duration) {
  const double seconds = static_cast<double>(duration.count()) / 1000.0;
  std::string text = std::to_string(seconds);
  text.erase(text.find_last_not_of('0') + 1);
  if (!text.empty() && text.back() == '.') text.pop_back();
  return text + " s";
}

}  // namespace

std::string StoreLock::LockPath(const std::string& database_path) {
  return database_path + ".lock";
}

pid_t StoreLock::RecordedHolder(const std::string& database_path) {
  std::ifstream file(LockPath(database_path));
  long pid = 0;
  if (!(file >> pid) || pid <= 0) return 0;
  return static_cast<pid_t>(pid);
}

StatusOr<std::unique_ptr<StoreLock>> StoreLock::Acquire(const std::string& database_path,
                                                        std::chrono::milliseconds timeout,
                                                        const WaitNotice& on_wait) {
  const std::string path = LockPath(database_path);
  const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd < 0) {
    const std::string message = database_path + ": opening: cannot create its lock file " + path +
                                ": " + std::strerror(errno);
    return errno == ENOENT ? NotFoundError(message) : UnavailableError(message);
  }
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  bool waiting = false;
  while (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
    if (errno == EINTR) continue;
    if (errno != EWOULDBLOCK) {
      const std::string reason = std::strerror(errno);
      ::close(fd);
      return UnavailableError(path + ": cannot lock the map store: " + reason);
    }
    const pid_t holder = RecordedHolder(database_path);
    if (std::chrono::steady_clock::now() >= deadline) {
      ::close(fd);
      return InvalidArgumentError(
          database_path + ": the map store is in use by another writer (" + Holder(holder) +
          " holds " + path + ")" +
          (timeout.count() > 0 ? ", still after waiting " + Seconds(timeout) : "") +
          ": one server per store; stop it first, or give this one another --store");
    }
    if (!waiting && on_wait) {
      on_wait(database_path + " is in use by " + Holder(holder) + ": waiting up to " +
              Seconds(timeout) + " for it to close the store");
    }
    waiting = true;
    std::this_thread::sleep_for(kRetryPeriod);
  }
  // Ours: say who holds it, replacing whatever pid an earlier holder left.
  const std::string pid = std::to_string(::getpid()) + "\n";
  // Should this fail, the lock holds all the same: only a refused writer's message lacks the pid.
  const ssize_t written = ::ftruncate(fd, 0) == 0 ? ::pwrite(fd, pid.data(), pid.size(), 0) : -1;
  (void)written;
  return std::unique_ptr<StoreLock>(new StoreLock(path, fd));
}

StoreLock::~StoreLock() {
  // Closing the last descriptor releases the lock. The pid stays: it is only read while the lock
  // is held, and the next holder replaces it.
  if (fd_ >= 0) ::close(fd_);
}

}  // namespace fleetmap::store
