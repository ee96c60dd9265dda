#pragma once

#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "common/core/ids.hpp"
#include "common/core/robot_status.hpp"
#include "common/core/status.hpp"
#include "common/store/map_store.hpp"
#include "common/vector_map/tiled_vector_map.hpp"

namespace fleetmap::server {

// One robot's map of one mapping session, in the fleet frame.
struct MappingSession {
  int64_t id = 0;  // the store's id, or a counter without a store; increases
  RobotId robot;
  Timestamp started{};
  Timestamp ended{};
  vector_map::TiledVectorMap map;
};

// The mapping sessions the server has seen: a session is one robot's tiles from its first tile
// until it leaves or is lost. Finished sessions are maps of the same place taken at different
// times, the object learner's input; they are kept in the store (when there is one) and read
// back at start, so a restarted server learns from what it saw before. Memory holds the newest
// `keep_in_memory` of them (what the learner reads); the store holds them all.
//
// Not thread-safe: the fusion worker owns it.
class SessionArchive {
 public:
  // `store` may be null (sessions live in memory only); it must outlive the archive.
  SessionArchive(double tile_size, store::MapStore* store, size_t keep_in_memory)
      : tile_size_(tile_size), store_(store), keep_in_memory_(keep_in_memory) {}

  // Reads the finished sessions kept in the store. A session whose payload does not decode is
  // skipped and named in the returned warnings.
  StatusOr<std::vector<std::string>> Restore();

  // A tile of the robot's open session (the first tile opens one). Tiles of a robot whose
  // session ended are held back: late samples of the session that ended are dropped by the next
  // EndSession(), and a robot that comes back (Rejoin) starts its new session with them.
  void RecordTile(const RobotId& robot, const TileId& tile, const vector_map::VectorMap& map,
                  Timestamp stamp);
  void RemoveTile(const RobotId& robot, const TileId& tile);
  // The robot is active again after its session ended.
  void Rejoin(const RobotId& robot);

  // Ends the robot's open session. Returns the finished session, or nullopt when the robot had no
  // open session with tiles. Fails only when the store refused it; it is kept in memory then.
  StatusOr<std::optional<MappingSession>> EndSession(const RobotId& robot, Timestamp ended);
  // Ends the robot's open session without keeping it (a map that is not a map of the place: cut
  // by a budget, or contradicting the fleet). Returns how many tiles it held.
  size_t DiscardSession(const RobotId& robot);
  bool has_open_session(const RobotId& robot) const { return open_.count(robot) > 0; }

  // The newest finished sessions, oldest first (at most keep_in_memory).
  const std::vector<MappingSession>& finished() const { return finished_; }
  // Every session finished or restored so far.
  size_t finished_count() const { return finished_count_; }
  size_t open_sessions() const { return open_.size(); }

 private:
  double tile_size_;
  store::MapStore* store_;
  std::map<RobotId, MappingSession> open_;  // by robot
  std::map<RobotId, MappingSession> held_;  // by robot: tiles after its session ended
  std::set<RobotId> closed_;                // robots whose session ended and that have not rejoined
  void Keep(MappingSession session);

  size_t keep_in_memory_;
  std::vector<MappingSession> finished_;  // oldest first, the newest keep_in_memory_
  size_t finished_count_ = 0;
  int64_t next_memory_id_ = 1;
};

}  // namespace fleetmap::server
