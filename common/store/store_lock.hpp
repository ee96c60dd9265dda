#pragma once

#include <sys/types.h>

#include <chrono>
#include <functional>
#include <memory>
#include <string>

#include "common/core/status.hpp"

namespace fleetmap::store {

// One writer per map store: an exclusive flock(2) on "<database>.lock" beside the database, which
// holds the holder's process id. The kernel releases the lock when the holder exits however it
// exits (SIGKILL included), so a stale file never blocks; the file itself is left in place, since
// deleting it would let a waiter lock a file nobody else sees. Readers (a plain SQLite connection)
// do not take it and are never blocked by it.
//
// Locks belong to the open file, not the process: a second Acquire in the same process waits and
// fails like a second process. Not thread-safe; destroy it to release the lock.
class StoreLock {
 public:
  // Called once, when the lock is held by another process and Acquire starts waiting: a sentence
  // naming the store, the holder's pid and how long it will wait.
  using WaitNotice = std::function<void(const std::string&)>;

  // Takes the lock of `database_path`, waiting up to `timeout` (0: not at all) for its holder to
  // release it. kInvalidArgument, naming the store and the holder's pid, when it is still held
  // after the timeout; kNotFound when its folder does not exist, kUnavailable when the lock file
  // cannot be created or locked otherwise.
  static StatusOr<std::unique_ptr<StoreLock>> Acquire(const std::string& database_path,
                                                      std::chrono::milliseconds timeout,
                                                      const WaitNotice& on_wait = nullptr);
  ~StoreLock();
  StoreLock(const StoreLock&) = delete;
  StoreLock& operator=(const StoreLock&) = delete;

  // "<database>.lock".
  static std::string LockPath(const std::string& database_path);
  // The pid written in `database_path`'s lock file, or 0 when there is none (no file, empty, or
  // being rewritten). Says who holds it only while it is held.
  static pid_t RecordedHolder(const std::string& database_path);

  const std::string& path() const { return path_; }

 private:
  StoreLock(std::string path, int fd) : path_(std::move(path)), fd_(fd) {}

  std::string path_;
  int fd_ = -1;
};

}  // namespace fleetmap::store
