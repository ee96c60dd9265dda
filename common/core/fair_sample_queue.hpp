#pragma once

#include <cstddef>
#include <deque>
#include <limits>
#include <map>
#include <mutex>
#include <string>
#include <vector>

namespace fleetmap {

// A queue from producer threads (a DDS listener) to one worker, fair between sources (e.g. the
// DDS participants that wrote the samples): Drain() takes one item from each source in turn,
// oldest first within a source, so one source's backlog never stands in front of another's
// items. Bounded: when full, Push() drops the oldest item of the source that holds the most,
// and counts it (dropped()), so a flooding source pays for its own flood. Thread-safe.
template <typename T>
class FairSampleQueue {
 public:
  explicit FairSampleQueue(size_t capacity = 4096) : capacity_(capacity) {}

  void Push(const std::string& source, T item) {
    std::lock_guard lock(mutex_);
    if (size_ >= capacity_) DropFromLargestSource();
    queues_[source].push_back(std::move(item));
    ++size_;
  }

  // At most `max_items`, one per source in turn (sources in key order, starting after the
  // source the last Drain() ended with); what is left waits for the next call.
  std::vector<T> Drain(size_t max_items = std::numeric_limits<size_t>::max()) {
    std::lock_guard lock(mutex_);
    std::vector<T> out;
    while (out.size() < max_items && size_ > 0) {
      auto it = queues_.upper_bound(last_source_);
      if (it == queues_.end()) it = queues_.begin();
      out.push_back(std::move(it->second.front()));
      it->second.pop_front();
      --size_;
      last_source_ = it->first;
      if (it->second.empty()) queues_.erase(it);
    }
    return out;
  }

  size_t size() const {
    std::lock_guard lock(mutex_);
    return size_;
  }

  // Items dropped because the queue was full, since it was made.
  size_t dropped() const {
    std::lock_guard lock(mutex_);
    return dropped_;
  }

 private:
  void DropFromLargestSource() {
    auto largest = queues_.begin();
    for (auto it = queues_.begin(); it != queues_.end(); ++it) {
      if (it->second.size() > largest->second.size()) largest = it;
    }
    if (largest == queues_.end()) return;
    largest->second.pop_front();
    if (largest->second.empty()) queues_.erase(largest);
    --size_;
    ++dropped_;
  }

  const size_t capacity_;
  mutable std::mutex mutex_;
  std::map<std::string, std::deque<T>> queues_;  // guarded by mutex_; no empty deques
  std::string last_source_;                      // guarded by mutex_
  size_t size_ = 0;                              // guarded by mutex_
  size_t dropped_ = 0;                           // guarded by mutex_
};

}  // namespace fleetmap
