#include "robot_agent/id_claim_watch.hpp"

#include <fmt/format.h>

namespace fleetmap::agent {

StatusOr<std::unique_ptr<IdClaimWatch>> IdClaimWatch::Create(transport::Participant& participant,
                                                             RobotId robot) {
  std::unique_ptr<IdClaimWatch> watch(new IdClaimWatch(std::move(robot), participant.id()));
  watch->domain_id_ = participant.domain_id();
  FLEETMAP_ASSIGN_OR_RETURN(watch->reader_, transport::RobotStatusReader::CreateForRobot(
                                                participant, watch->robot_, watch->wake_up_));
  return watch;
}

std::vector<std::string> IdClaimWatch::NewClaimants() {
  std::vector<std::string> found;
  for (const transport::RobotEvent& event : reader_->Drain()) {
    if (event.kind != transport::RobotEvent::Kind::kStatus || event.robot != robot_) continue;
    const std::string participant = event.writer.substr(0, 24);
    if (participant == own_participant_) continue;
    if (claimants_.insert(participant).second) found.push_back(participant);
  }
  return found;
}

Status IdClaimWatch::CheckIdIsFree(std::chrono::milliseconds wait) {
  const auto deadline = std::chrono::steady_clock::now() + wait;
  while (true) {
    const std::vector<std::string> others = NewClaimants();
    if (!others.empty()) {
      return InvalidArgumentError(fmt::format(
          "robot id {} is already taken on DDS domain {} by participant {} (another agent, or "
          "a peer speaking for it): the server keeps the first claim and would ignore this "
          "agent; choose another --robot-id, or stop the other",
          robot_.value, domain_id_, others.front()));
    }
    const auto now = std::chrono::steady_clock::now();
    if (now >= deadline) return Status::Ok();
    wake_up_->WaitFor(std::chrono::duration_cast<std::chrono::milliseconds>(deadline - now));
  }
}

}  // namespace fleetmap::agent
