#pragma once

#include <cstddef>
#include <functional>
#include <map>
#include <mutex>
#include <optional>
#include <set>
#include <string>

#include "common/core/ids.hpp"

namespace fleetmap::server {

// Which agent speaks for which robot id: the DDS participant (the first 24 hex digits of a writer
// id) whose status claimed the id first, for as long as that robot is alive. A second agent with
// the same id is a misconfiguration or a hijack attempt: its statuses, disposals, tiles and
// entities are refused and reported, never merged. Without DDS Security a participant is not
// authenticated, so this stops mistakes and casual forgery, not a peer that claims an id first.
// With DDS Security (RequireIdentity) a participant speaks only for the robot it authenticated
// as, even if its permissions were written too wide: defence in depth.
// Thread-safe: the control thread claims and releases, the fusion worker checks.
class RobotRegistry {
 public:
  enum class Claim {
    kNew,        // the id was free: now it is this participant's
    kSame,       // the participant already owns it
    kClash,      // another participant owns it
    kTooMany,    // the participant already owns max_robots_per_participant ids
    kNotItself,  // with RequireIdentity: the participant authenticated under another name
  };
  // The authenticated name of the participant that owns a writer id, or nullopt if it has none.
  using IdentityLookup = std::function<std::optional<std::string>(const std::string& writer)>;
  enum class Speaker {
    kOwner,
    kUnclaimed,
    kOverCap,  // unclaimed, but the writer's participant already speaks for its maximum of ids
    kOther,
    kNotItself,  // with RequireIdentity: the writer authenticated as another name
  };

  explicit RobotRegistry(size_t max_robots_per_participant = 16)
      : max_robots_per_participant_(max_robots_per_participant) {}

  // From now on, a participant may claim and speak only for the robot id it authenticated as.
  void RequireIdentity(IdentityLookup lookup);

  // Claims `robot` for the participant of `writer`. A new claim also records whether the robot's
  // tiles come in its own map frame (its agent does not know where that frame sits in the fleet;
  // the server places it): with the claim, so the fusion worker never sees one without the other.
  Claim ClaimRobot(const RobotId& robot, const std::string& writer,
                   bool tiles_in_map_frame = false);
  // Frees the id when its robot left or was lost, if `writer` speaks for its owner; returns
  // whether it did.
  bool Release(const RobotId& robot, const std::string& writer);
  // Who `writer` is to `robot`.
  Speaker WhoSpeaks(const RobotId& robot, const std::string& writer) const;
  // The participant owning `robot`, or empty.
  std::string OwnerOf(const RobotId& robot) const;
  // Whether the robot's tiles come in its own map frame (as its last new claim said).
  bool TilesInMapFrame(const RobotId& robot) const;
  // Every robot whose tiles come in its own map frame.
  std::set<RobotId> MapFrameRobots() const;

  static std::string ParticipantOf(const std::string& writer) { return writer.substr(0, 24); }

 private:
  bool IsItself(const RobotId& robot, const std::string& writer) const;

  const size_t max_robots_per_participant_;
  IdentityLookup identity_;  // set before any claim
  mutable std::mutex mutex_;
  std::map<RobotId, std::string> participant_by_robot_;  // guarded by mutex_
  std::map<std::string, size_t> robots_by_participant_;  // guarded by mutex_
  std::set<RobotId> tiles_in_map_frame_;                 // guarded by mutex_
};

}  // namespace fleetmap::server
