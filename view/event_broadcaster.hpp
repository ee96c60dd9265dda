#pragma once

// Hands the view's events to every connected browser without letting any browser hold up DDS or
// the others. Each client has a bounded queue of deltas; the publisher only appends (never waits
// on a socket). A client that falls behind by more than the queue holds loses its queue and is
// sent the whole state instead (drop and resync); a client whose socket stalls past the web
// server's write timeout is disconnected by its own thread. The number of clients is bounded.

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

namespace fleetmap::view {

using Event = std::shared_ptr<const std::string>;

struct BroadcastLimits {
  size_t max_clients = 32;
  size_t max_queued_events = 64;  // per client; past this the client resyncs
};

struct BroadcastCounters {
  size_t clients = 0;
  uint64_t connected = 0;  // since start
  uint64_t refused = 0;    // connections past max_clients
  uint64_t resyncs = 0;    // queues dropped for a whole state
  uint64_t events = 0;     // deltas published
};

class EventBroadcaster {
 public:
  class Client;

  explicit EventBroadcaster(BroadcastLimits limits = {});

  // A new client, whose first event will be the whole state; nullptr when max_clients are
  // connected.
  std::shared_ptr<Client> Connect();
  void Disconnect(const std::shared_ptr<Client>& client);

  // True when some client waits for the whole state: the publisher then passes one to Publish.
  bool WantsFullState() const;
  // Queues `delta` for every client that is in step, and `full` (if given) for every client that
  // waits for it instead of the delta (`full` must already contain `delta`'s changes).
  void Publish(const Event& delta, const Event& full);
  // Wakes every client thread, which then sees Next() return nullopt: the view is stopping.
  void Close();

  // For a client's own thread: the next event to send. Waits up to `timeout` (then returns an
  // empty event: time for a keep-alive), and returns nullopt once closed or disconnected.
  std::optional<Event> Next(Client& client, std::chrono::milliseconds timeout);

  BroadcastCounters counters() const;

 private:
  BroadcastLimits limits_;
  mutable std::mutex mutex_;
  std::condition_variable ready_;
  std::vector<std::shared_ptr<Client>> clients_;
  BroadcastCounters counters_;
  bool closed_ = false;
};

class EventBroadcaster::Client {
 private:
  friend class EventBroadcaster;
  std::deque<Event> queue;
  bool wants_full = true;
  bool connected = true;
};

}  // namespace fleetmap::view
