#include "server/robot_registry.hpp"

namespace fleetmap::server {

RobotRegistry::Claim RobotRegistry::ClaimRobot(const std::string& robot,
                                               const std::string& writer) {
  std::lock_guard lock(mutex_);
  const std::string participant = ParticipantOf(writer);
  const auto [it, inserted] = participant_by_robot_.emplace(robot, participant);
  if (inserted) return Claim::kNew;
  return it->second == participant ? Claim::kSame : Claim::kClash;
}

void RobotRegistry::Release(const std::string& robot) {
  std::lock_guard lock(mutex_);
  participant_by_robot_.erase(robot);
}

bool RobotRegistry::MaySpeakFor(const std::string& robot, const std::string& writer) const {
  std::lock_guard lock(mutex_);
  const auto it = participant_by_robot_.find(robot);
  return it == participant_by_robot_.end() || it->second == ParticipantOf(writer);
}

}  // namespace fleetmap::server
