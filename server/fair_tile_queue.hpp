#pragma once

#include <chrono>
#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "common/core/ids.hpp"

namespace fleetmap::server {

// Robot tiles waiting for fusion, served fairly: each robot's queue keeps only the newest
// revision of each tile (a robot that sends the same tiles faster than they are fused costs no
// memory beyond its tiles), and the robot served next is the one that has used the least fusion
// time (start-time fair queueing), so one robot's flood cannot delay another's updates by more
// than one turn. Not thread-safe: the fusion worker owns it.
template <typename Item>
class FairTileQueue {
 public:
  using Duration = std::chrono::nanoseconds;

  // Queues `item` for `robot`'s `tile`, replacing an older one of the same tile.
  void Push(const std::string& robot, const TileId& tile, Item item) {
    Robot& queue = robots_[robot];
    if (queue.pending.empty()) {
      // A robot that was idle starts level with the others: idle time is not credit.
      queue.virtual_time = std::max(queue.virtual_time, virtual_now_);
    }
    const auto [it, inserted] = queue.pending.insert_or_assign(tile, std::move(item));
    if (inserted) {
      queue.order.push_back(tile);
      ++size_;
    }
  }

  // The next turn: up to `max_items` of the robot that used the least fusion time, oldest first.
  // Empty when nothing waits. Charge() the turn's cost to `robot` afterwards.
  std::vector<Item> NextTurn(size_t max_items, std::string* robot) {
    std::vector<Item> turn;
    auto chosen = robots_.end();
    for (auto it = robots_.begin(); it != robots_.end(); ++it) {
      if (it->second.pending.empty()) continue;
      if (chosen == robots_.end() || it->second.virtual_time < chosen->second.virtual_time) {
        chosen = it;
      }
    }
    if (chosen == robots_.end()) return turn;
    *robot = chosen->first;
    Robot& queue = chosen->second;
    virtual_now_ = std::max(virtual_now_, queue.virtual_time);
    size_t taken = 0;
    while (taken < queue.order.size() && turn.size() < max_items) {
      const TileId tile = queue.order[taken++];
      const auto it = queue.pending.find(tile);
      turn.push_back(std::move(it->second));
      queue.pending.erase(it);
    }
    queue.order.erase(queue.order.begin(), queue.order.begin() + static_cast<ptrdiff_t>(taken));
    size_ -= turn.size();
    return turn;
  }

  // Fusion time spent on `robot`'s turn.
  void Charge(const std::string& robot, Duration used) {
    const auto it = robots_.find(robot);
    if (it != robots_.end()) it->second.virtual_time += used;
  }

  // Drops what waits for `robot`'s `tile` (its robot removed it).
  void Erase(const std::string& robot, const TileId& tile) {
    const auto it = robots_.find(robot);
    if (it == robots_.end() || it->second.pending.erase(tile) == 0) return;
    std::erase(it->second.order, tile);
    --size_;
  }

  size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }

 private:
  struct Robot {
    std::map<TileId, Item> pending;
    std::vector<TileId> order;  // arrival order of the pending tiles
    Duration virtual_time{0};   // fusion time used, as seen by the scheduler
  };

  std::map<std::string, Robot> robots_;
  Duration virtual_now_{0};
  size_t size_ = 0;
};

}  // namespace fleetmap::server
