#pragma once

#include <cstddef>
#include <deque>
#include <iterator>
#include <mutex>
#include <vector>

namespace fleetmap {

// A queue from producer threads (a DDS listener, Submit() calls) to one worker that drains it.
// Thread-safe. Bounded: when full, Push() drops the oldest item and counts it (dropped()), so a
// stalled worker cannot exhaust memory and the newest state still gets through.
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

  // Everything queued, oldest first; the queue is empty afterwards.
  std::vector<T> Drain() {
    std::lock_guard lock(mutex_);
    std::vector<T> out(std::make_move_iterator(items_.begin()),
                       std::make_move_iterator(items_.end()));
    items_.clear();
    return out;
  }

  // Items dropped because the queue was full, since it was made.
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

}  // namespace fleetmap
