#pragma once

// Internal to transport: a participant's writers on the exclusive topics (served_state.hpp). It
// asserts their liveliness, which their readers watch to leave a dead server, and writes their
// state again when the server starts serving.

#include <condition_variable>
#include <mutex>
#include <set>
#include <thread>

namespace fleetmap::transport {

class WriterEndpoint;

class ServedWriters {
 public:
  ServedWriters() = default;
  // Stops the thread. Every writer was removed (writers go before their participant).
  ~ServedWriters();
  ServedWriters(const ServedWriters&) = delete;
  ServedWriters& operator=(const ServedWriters&) = delete;

  // The first writer starts a thread that asserts every writer's liveliness four times a lease.
  void Add(WriterEndpoint* writer);
  void Remove(WriterEndpoint* writer);
  // Every writer's instances written again; the number of instances.
  size_t WriteAgain();

 private:
  void AssertLoop();

  std::mutex mutex_;
  std::condition_variable stop_cv_;
  bool stop_ = false;                  // guarded by mutex_
  std::set<WriterEndpoint*> writers_;  // guarded by mutex_
  std::thread asserter_;
};

}  // namespace fleetmap::transport
