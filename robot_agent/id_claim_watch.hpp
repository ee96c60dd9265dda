#pragma once

#include <memory>
#include <set>
#include <string>
#include <vector>

#include "common/core/ids.hpp"
#include "common/core/status.hpp"
#include "common/transport/participant.hpp"
#include "common/transport/robot_status_reader.hpp"

namespace fleetmap::agent {

// Watches rt/fleetmap/robot_status for other DDS participants that claim this agent's robot id.
// The server keeps a robot id for the participant that claimed it first, so an agent that finds
// its id taken when it starts must not go on as if it were in the fleet. Not thread-safe.
class IdClaimWatch {
 public:
  static StatusOr<std::unique_ptr<IdClaimWatch>> Create(transport::Participant& participant,
                                                        RobotId robot);

  // The participants other than this one seen claiming the robot id since the last call.
  std::vector<std::string> NewClaimants();

  // Waits up to `wait` (discovery time) for another participant's claim; an error naming it
  // when there is one.
  Status CheckIdIsFree(std::chrono::milliseconds wait);

 private:
  IdClaimWatch(RobotId robot, std::string own_participant)
      : robot_(std::move(robot)), own_participant_(std::move(own_participant)) {}

  RobotId robot_;
  std::string own_participant_;
  int domain_id_ = 0;
  std::shared_ptr<WakeUp> wake_up_ = std::make_shared<WakeUp>();
  std::unique_ptr<transport::RobotStatusReader> reader_;
  std::set<std::string> claimants_;
};

}  // namespace fleetmap::agent
