#include "server/robot_registry.hpp"

namespace fleetmap::server {

void RobotRegistry::RequireIdentity(IdentityLookup lookup) {
  std::lock_guard lock(mutex_);
  identity_ = std::move(lookup);
}

bool RobotRegistry::IsItself(const RobotId& robot, const std::string& writer) const {
  if (!identity_) return true;
  const std::optional<std::string> name = identity_(writer);
  return name.has_value() && *name == robot.value;
}

RobotRegistry::Claim RobotRegistry::ClaimRobot(const RobotId& robot, const std::string& writer,
                                               bool tiles_in_map_frame) {
  std::lock_guard lock(mutex_);
  if (!IsItself(robot, writer)) return Claim::kNotItself;
  const std::string participant = ParticipantOf(writer);
  const auto it = participant_by_robot_.find(robot);
  if (it != participant_by_robot_.end()) {
    return it->second == participant ? Claim::kSame : Claim::kClash;
  }
  size_t& owned = robots_by_participant_[participant];
  if (owned >= max_robots_per_participant_) return Claim::kTooMany;
  ++owned;
  participant_by_robot_.emplace(robot, participant);
  if (tiles_in_map_frame) {
    tiles_in_map_frame_.insert(robot);
  } else {
    tiles_in_map_frame_.erase(robot);
  }
  return Claim::kNew;
}

bool RobotRegistry::Release(const RobotId& robot, const std::string& writer) {
  std::lock_guard lock(mutex_);
  const auto it = participant_by_robot_.find(robot);
  if (it == participant_by_robot_.end() || it->second != ParticipantOf(writer)) return false;
  const auto owned = robots_by_participant_.find(it->second);
  if (owned != robots_by_participant_.end() && --owned->second == 0) {
    robots_by_participant_.erase(owned);
  }
  participant_by_robot_.erase(it);
  return true;
}

RobotRegistry::Speaker RobotRegistry::WhoSpeaks(const RobotId& robot,
                                                const std::string& writer) const {
  std::lock_guard lock(mutex_);
  if (!IsItself(robot, writer)) return Speaker::kNotItself;
  const auto it = participant_by_robot_.find(robot);
  const std::string participant = ParticipantOf(writer);
  if (it == participant_by_robot_.end()) {
    // Its claim would be refused: what it sends for the id need not wait for a status.
    const auto owned = robots_by_participant_.find(participant);
    const bool full =
        owned != robots_by_participant_.end() && owned->second >= max_robots_per_participant_;
    return full ? Speaker::kOverCap : Speaker::kUnclaimed;
  }
  return it->second == participant ? Speaker::kOwner : Speaker::kOther;
}

std::string RobotRegistry::OwnerOf(const RobotId& robot) const {
  std::lock_guard lock(mutex_);
  const auto it = participant_by_robot_.find(robot);
  return it == participant_by_robot_.end() ? std::string() : it->second;
}

bool RobotRegistry::TilesInMapFrame(const RobotId& robot) const {
  std::lock_guard lock(mutex_);
  return tiles_in_map_frame_.count(robot) > 0;
}

std::set<RobotId> RobotRegistry::MapFrameRobots() const {
  std::lock_guard lock(mutex_);
  return tiles_in_map_frame_;
}

}  // namespace fleetmap::server
