#pragma once

// One section of the page's state (tiles, robots, sub-maps, ...): items by key, each kept as the
// JSON the page receives, and which keys changed since the last delta was taken. A removed item
// goes out as null, which is how the page learns to forget it.

#include <map>
#include <set>
#include <string>

#include <nlohmann/json.hpp>

namespace fleetmap::view {

class JsonDictionary {
 public:
  // Stores `item` under `key`; a no-op (nothing to send) when it equals what is stored.
  void Put(const std::string& key, nlohmann::json item) {
    auto [it, inserted] = items_.try_emplace(key, nlohmann::json());
    if (!inserted && it->second == item) return;
    it->second = std::move(item);
    changed_.insert(key);
  }
  void Remove(const std::string& key) {
    if (items_.erase(key) > 0) changed_.insert(key);
  }

  // Every item: {key: item, ...}.
  nlohmann::json All() const {
    nlohmann::json all = nlohmann::json::object();
    for (const auto& [key, item] : items_) all[key] = item;
    return all;
  }
  // The items changed since the last call (null for removed ones), and forgets them.
  nlohmann::json TakeChanges() {
    nlohmann::json changes = nlohmann::json::object();
    for (const std::string& key : changed_) {
      const auto it = items_.find(key);
      changes[key] = it == items_.end() ? nlohmann::json(nullptr) : it->second;
    }
    changed_.clear();
    return changes;
  }

  size_t size() const { return items_.size(); }
  bool contains(const std::string& key) const { return items_.count(key) > 0; }
  const std::map<std::string, nlohmann::json>& items() const { return items_; }

 private:
  std::map<std::string, nlohmann::json> items_;
  std::set<std::string> changed_;
};

}  // namespace fleetmap::view
