#pragma once

#include <memory>
#include <set>
#include <vector>

#include "common/core/robot_status.hpp"
#include "common/core/status.hpp"
#include "common/transport/participant.hpp"

namespace fleetmap::transport {

class WriterEndpoint;

// An agent's writer of its own RobotStatus on rt/fleetmap/robot_status. Its liveliness tells the
// server the robot is alive; Leave() disposes the robot's instance (it went away on purpose).
// One writer may speak for several robots (a simulator, a test).
// Call from one thread.
class RobotStatusWriter {
 public:
  static StatusOr<std::unique_ptr<RobotStatusWriter>> Create(Participant& participant);
  ~RobotStatusWriter();

  Status Write(const RobotStatus& status);
  Status Leave(const RobotId& robot);
  // Several robots leave at once: one wait for the readers' acknowledgements, not one per robot.
  Status Leave(const std::vector<RobotId>& robots);
  int matched_readers() const;

 private:
  RobotStatusWriter() = default;
  std::unique_ptr<WriterEndpoint> endpoint_;
  std::set<RobotId> written_;  // robots whose instance this writer has announced
};

}  // namespace fleetmap::transport
