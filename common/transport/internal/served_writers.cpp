#include "common/transport/internal/served_writers.hpp"

#include "common/transport/internal/endpoint.hpp"
#include "common/transport/served_state.hpp"

namespace fleetmap::transport {

ServedWriters::~ServedWriters() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  stop_cv_.notify_all();
  if (asserter_.joinable()) asserter_.join();
}

void ServedWriters::Add(WriterEndpoint* writer) {
  std::lock_guard lock(mutex_);
  writers_.insert(writer);
  if (!asserter_.joinable()) asserter_ = std::thread([this] { AssertLoop(); });
}

void ServedWriters::Remove(WriterEndpoint* writer) {
  std::lock_guard lock(mutex_);
  writers_.erase(writer);
}

size_t ServedWriters::WriteAgain() {
  std::lock_guard lock(mutex_);
  size_t written = 0;
  for (WriterEndpoint* writer : writers_) written += writer->WriteAgain();
  return written;
}

void ServedWriters::AssertLoop() {
  std::unique_lock lock(mutex_);
  while (!stop_) {
    // Writing asserts liveliness too; an idle topic still needs these.
    for (WriterEndpoint* writer : writers_) writer->writer()->assert_liveliness();
    stop_cv_.wait_for(lock, kServedLivelinessLease / 4, [this] { return stop_; });
  }
}

}  // namespace fleetmap::transport
