#pragma once

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "common/core/ids.hpp"

namespace fleetmap::fusion {

// Robot tiles waiting for fusion, served fairly between payers: each payer's queue keeps only the
// newest revision of each key (a robot that sends the same tiles faster than they are fused costs
// no memory beyond its tiles), and the payer served next is the one that has used the least
// fusion time (start-time fair queueing), so one payer's flood cannot delay another's updates by
// more than one turn. The payer is a robot id, or (in the server) the DDS participant that sent
// the tiles, so that many ids of one participant share one place in the queue. A turn is sized by
// what the payer's tiles have cost so far: as many as fit in a target time, at least one, so a
// payer whose tiles are expensive (hostile or not) takes short turns. Not thread-safe: the fusion
// worker owns it.
template <typename Item, typename Payer = RobotId, typename Key = TileId>
class FairTileQueue {
 public:
  using Duration = std::chrono::nanoseconds;

  // Queues `item` for `robot`'s `tile`, replacing an older one of the same tile.
  void Push(const Payer& robot, const Key& tile, Item item) {
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

  // The next turn: of the robot that used the least fusion time, oldest first, as many items as
  // its cost per item (see Charge) fits in `target` (at least one, at most `max_items`; one while
  // its cost is unknown). Empty when nothing waits. Charge() the turn's cost to `robot` afterwards.
  std::vector<Item> NextTurn(size_t max_items, Duration target, Payer* robot) {
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
    if (queue.cost_per_item.count() > 0) {
      max_items =
          std::clamp<size_t>(static_cast<size_t>(target / queue.cost_per_item), 1, max_items);
    } else {
      max_items = std::min<size_t>(max_items, kItemsWhileCostUnknown);
    }
    size_t taken = 0;
    while (taken < queue.order.size() && turn.size() < max_items) {
      const Key tile = queue.order[taken++];
      const auto it = queue.pending.find(tile);
      turn.push_back(std::move(it->second));
      queue.pending.erase(it);
    }
    queue.order.erase(queue.order.begin(), queue.order.begin() + static_cast<ptrdiff_t>(taken));
    size_ -= turn.size();
    return turn;
  }

  // Fusion time spent on `robot`'s turn of `items` items.
  void Charge(const Payer& robot, Duration used, size_t items) {
    const auto it = robots_.find(robot);
    if (it == robots_.end()) return;
    Robot& queue = it->second;
    queue.virtual_time += used;
    if (items == 0) return;
    const Duration per_item = used / static_cast<int64_t>(items);
    // Up at once, down slowly: a turn sized by an average of costs that vary (random heavy tiles,
    // a core shared with other processes) overruns its target by as much as they vary, and every
    // other payer's update waits for that overrun. Costs still fall as a robot's tiles get cheaper.
    queue.cost_per_item =
        per_item >= queue.cost_per_item ? per_item : (queue.cost_per_item * 3 + per_item) / 4;
  }

  // Drops what waits for `robot`'s `tile` (its robot removed it).
  void Erase(const Payer& robot, const Key& tile) {
    const auto it = robots_.find(robot);
    if (it == robots_.end() || it->second.pending.erase(tile) == 0) return;
    std::erase(it->second.order, tile);
    --size_;
  }

  // Drops every waiting item whose key satisfies `drop` (a robot refused or over its budget:
  // its queued work must not delay the others); returns how many.
  template <typename Predicate>
  size_t EraseIf(Predicate drop) {
    size_t erased = 0;
    for (auto& [payer, queue] : robots_) {
      erased += std::erase_if(queue.pending, [&](const auto& entry) { return drop(entry.first); });
      std::erase_if(queue.order, [&](const Key& key) { return queue.pending.count(key) == 0; });
    }
    size_ -= erased;
    return erased;
  }

  size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }

 private:
  // A new payer's first turn is one item: its cost is unknown, and it may be anything.
  static constexpr size_t kItemsWhileCostUnknown = 1;

  struct Robot {
    std::map<Key, Item> pending;
    std::vector<Key> order;     // arrival order of the pending tiles
    Duration virtual_time{0};   // fusion time used, as seen by the scheduler
    Duration cost_per_item{0};  // what one item costs (see Charge); 0: unknown
  };

  std::map<Payer, Robot> robots_;
  Duration virtual_now_{0};
  size_t size_ = 0;
};

}  // namespace fleetmap::fusion
