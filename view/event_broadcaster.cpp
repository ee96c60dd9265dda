#include "view/event_broadcaster.hpp"

#include <algorithm>

namespace fleetmap::view {

EventBroadcaster::EventBroadcaster(BroadcastLimits limits) : limits_(limits) {}

std::shared_ptr<EventBroadcaster::Client> EventBroadcaster::Connect() {
  std::lock_guard lock(mutex_);
  if (closed_ || clients_.size() >= limits_.max_clients) {
    ++counters_.refused;
    return nullptr;
  }
  auto client = std::make_shared<Client>();
  clients_.push_back(client);
  ++counters_.connected;
  return client;
}

void EventBroadcaster::Disconnect(const std::shared_ptr<Client>& client) {
  std::lock_guard lock(mutex_);
  client->connected = false;
  client->queue.clear();
  clients_.erase(std::remove(clients_.begin(), clients_.end(), client), clients_.end());
  ready_.notify_all();
}

bool EventBroadcaster::WantsFullState() const {
  std::lock_guard lock(mutex_);
  return std::any_of(clients_.begin(), clients_.end(),
                     [](const auto& client) { return client->wants_full; });
}

void EventBroadcaster::Publish(const Event& delta, const Event& full) {
  std::lock_guard lock(mutex_);
  if (delta != nullptr) ++counters_.events;
  for (const auto& client : clients_) {
    if (client->wants_full) {
      if (full == nullptr) continue;  // it gets a whole state on a later round
      client->queue.clear();
      client->queue.push_back(full);
      client->wants_full = false;
    } else if (delta != nullptr) {
      if (client->queue.size() >= limits_.max_queued_events) {
        // Too far behind to catch up by deltas: drop them, send the whole state next round.
        client->queue.clear();
        client->wants_full = true;
        ++counters_.resyncs;
        continue;
      }
      client->queue.push_back(delta);
    }
  }
  ready_.notify_all();
}

void EventBroadcaster::Close() {
  std::lock_guard lock(mutex_);
  closed_ = true;
  ready_.notify_all();
}

std::optional<Event> EventBroadcaster::Next(Client& client, std::chrono::milliseconds timeout) {
  std::unique_lock lock(mutex_);
  const bool woken = ready_.wait_for(
      lock, timeout, [&] { return closed_ || !client.connected || !client.queue.empty(); });
  if (closed_ || !client.connected) return std::nullopt;
  if (!woken) return Event();  // nothing to send: a keep-alive is due
  Event next = std::move(client.queue.front());
  client.queue.pop_front();
  return next;
}

BroadcastCounters EventBroadcaster::counters() const {
  std::lock_guard lock(mutex_);
  BroadcastCounters counters = counters_;
  counters.clients = clients_.size();
  return counters;
}

}  // namespace fleetmap::view
