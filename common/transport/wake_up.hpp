#pragma once

#include <chrono>
#include <condition_variable>
#include <deque>
#include <mutex>
#include <vector>

namespace fleetmap::transport {

// Wakes one worker thread when any of its readers has queued something. Readers call Notify()
// from DDS threads; the worker calls WaitFor() in its loop. Thread-safe.
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

 private:
  std::mutex mutex_;
  std::condition_variable condition_;
  bool pending_ = false;  // guarded by mutex_
};

// A queue from a DDS listener thread (Push) to the worker (Drain). Thread-safe. Bounded: when
// full, the oldest item is dropped and counted, so a stalled worker cannot exhaust memory.
template <typename T>
class SampleQueue {
 public:
  explicit SampleQueue(size_t capacity = 4096) : capacity_(capacity) {}

  void Push(T item) {
    std::lock_guard lock(mutex_);
    if (items_.size() >= capacity_) {
      items_.pop_front();
      ++dropped_;
    }
    items_.push_back(std::move(item));
  }

  std::vector<T> Drain() {
    std::lock_guard lock(mutex_);
    std::vector<T> out(std::make_move_iterator(items_.begin()),
                       std::make_move_iterator(items_.end()));
    items_.clear();
    return out;
  }

  size_t dropped() const {
    std::lock_guard lock(mutex_);
    return dropped_;
  }

 private:
  const size_t capacity_;
  mutable std::mutex mutex_;
  std::deque<T> items_;  // guarded by mutex_
  size_t dropped_ = 0;   // guarded by mutex_
};

}  // namespace fleetmap::transport
