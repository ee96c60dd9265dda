#pragma once

#include <chrono>
#include <condition_variable>
#include <mutex>

namespace fleetmap {

// Wakes one worker thread when something has queued work for it (a DDS reader's listener, another
// thread's Submit). Producers call Notify() from any thread; the worker waits in its loop.
// A Notify() with nobody waiting is remembered until the next wait. Thread-safe.
class WakeUp {
 public:
  void Notify() {
    {
      std::lock_guard lock(mutex_);
      pending_ = true;
    }
    condition_.notify_one();
  }

  // Returns true if notified (and clears it), false on timeout.
  bool WaitFor(std::chrono::milliseconds timeout) {
    std::unique_lock lock(mutex_);
    const bool notified = condition_.wait_for(lock, timeout, [this] { return pending_; });
    pending_ = false;
    return notified;
  }

  // Waits until notified (and clears it), however long that takes.
  void Wait() {
    std::unique_lock lock(mutex_);
    condition_.wait(lock, [this] { return pending_; });
    pending_ = false;
  }

 private:
  std::mutex mutex_;
  std::condition_variable condition_;
  bool pending_ = false;  // guarded by mutex_
};

}  // namespace fleetmap
