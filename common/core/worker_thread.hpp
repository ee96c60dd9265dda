#pragma once

#include <atomic>
#include <chrono>
#include <functional>
#include <memory>
#include <optional>
#include <thread>

#include "common/core/wake_up.hpp"

namespace fleetmap {

// The thread of a background worker and its loop: wait until woken (Wake(), or Notify() on
// wake_up() from a reader's listener) or until the wait times out, run one round; again, until
// Stop(). A round that reports work left is followed by the next one without waiting.
//
// Stop() sets the stop flag, wakes the thread and joins it. The loop checks the flag before each
// wait, so the round in progress completes, and a thread woken from its wait by Stop() runs one
// more round (which may call stopping() to skip its work); then `at_stop` runs, on the worker
// thread, and the loop ends. Whatever is queued after that is not handled.
//
// Threads: Start() and Stop() from the owner's thread (Stop() is idempotent, and harmless before
// Start()); Wake(), wake_up() and stopping() from any thread. The round and `at_stop` run on the
// worker thread only, so what only they touch needs no lock.
class WorkerThread {
 public:
  // One round of work; returns true when work is left, so that the next round starts at once.
  using Round = std::function<bool()>;

  // Waits at most `timeout` between rounds; std::nullopt: until woken, however long.
  explicit WorkerThread(std::optional<std::chrono::milliseconds> timeout) : timeout_(timeout) {}
  ~WorkerThread() { Stop(); }
  WorkerThread(const WorkerThread&) = delete;
  WorkerThread& operator=(const WorkerThread&) = delete;

  void Start(Round round, std::function<void()> at_stop = nullptr);
  void Stop();

  void Wake() { wake_up_->Notify(); }
  bool stopping() const { return stop_.load(); }
  // For readers whose listeners wake this worker when they queue a sample.
  const std::shared_ptr<WakeUp>& wake_up() const { return wake_up_; }

 private:
  void Loop();

  const std::optional<std::chrono::milliseconds> timeout_;
  const std::shared_ptr<WakeUp> wake_up_ = std::make_shared<WakeUp>();
  Round round_;                    // worker thread only, after Start()
  std::function<void()> at_stop_;  // worker thread only, after Start()
  std::atomic<bool> stop_{false};
  std::thread thread_;  // owner's thread only
};

}  // namespace fleetmap
