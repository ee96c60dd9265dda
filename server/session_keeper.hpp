#pragma once

#include <functional>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "common/core/ids.hpp"
#include "common/core/status.hpp"
#include "common/fusion/fleet_map.hpp"
#include "common/store/map_store.hpp"
#include "server/session_archive.hpp"

namespace fleetmap::server {

// Keeps each robot's mapping session for the object learner: what the robot contributes to the
// fleet map, from its first tile until it leaves or is lost. A session is kept only when it is a
// whole map of the place: not one a budget cut (the server never held all of it), not one of a
// quarantined robot (it contradicts the fleet). Not thread-safe: the fusion worker's.
class SessionKeeper {
 public:
  // Called with all finished sessions (oldest first) when one more finished.
  using Listener = std::function<void(std::vector<MappingSession> finished)>;

  // `store` may be null (sessions live in memory only); it must outlive the keeper.
  SessionKeeper(double tile_size, store::MapStore* store, size_t keep_in_memory)
      : archive_(tile_size, store, keep_in_memory) {}

  // Reads the finished sessions the store holds (skipped ones are named in the log).
  Status Restore();
  void SetListener(Listener listener) { listener_ = std::move(listener); }
  // Tells the listener of the sessions the store held, if any.
  void ReportRestored() {
    if (listener_ && !archive_.finished().empty()) listener_(archive_.finished());
  }

  // A robot's contribution changed or went: its open session follows.
  void Follow(const fusion::ContributionChange& change);
  // A robot's tile was refused: a refusal that cuts its map spoils the open session.
  void Refused(const RobotId& robot, fusion::Refusal reason);
  // Robot state changes ("active", "left", "lost"): a robot that left or was lost ends its
  // session, kept or not (`map` says whether it is quarantined). Returns how many store errors.
  size_t RobotsChanged(const std::vector<store::RobotRecord>& records, const fusion::FleetMap& map);

  const std::vector<MappingSession>& finished() const { return archive_.finished(); }
  size_t finished_count() const { return archive_.finished_count(); }

 private:
  // Why the robot's session, ending now, is not a map of the place (empty: it is kept).
  std::string WhyNotKept(const RobotId& robot, const fusion::FleetMap& map) const;

  SessionArchive archive_;
  std::set<RobotId> cut_;  // robots whose open session lost tiles to a budget
  Listener listener_;
};

}  // namespace fleetmap::server
