#include "common/transport/robot_status_writer.hpp"

#include <fastdds/dds/core/status/PublicationMatchedStatus.hpp>

#include "common/transport/internal/checked_type_support.hpp"
#include "common/transport/internal/conversions.hpp"
#include "common/transport/internal/endpoint.hpp"
#include "common/transport/internal/qos.hpp"
#include "common/transport/topics.hpp"
#include "fleetmap_msgs/msg/RobotStatus.h"

namespace fleetmap::transport {

namespace dds = eprosima::fastdds::dds;

StatusOr<std::unique_ptr<RobotStatusWriter>> RobotStatusWriter::Create(Participant& participant) {
  std::unique_ptr<RobotStatusWriter> self(new RobotStatusWriter());
  FLEETMAP_ASSIGN_OR_RETURN(
      self->endpoint_, WriterEndpoint::Create(participant, kRobotStatusTopic,
                                              RobotStatusTypeSupport(), RobotStatusQos().writer));
  return self;
}

RobotStatusWriter::~RobotStatusWriter() = default;

Status RobotStatusWriter::Write(const RobotStatus& status) {
  auto sample = ToIdl(status);
  if (!endpoint_->writer()->write(&sample)) {
    return UnavailableError("could not write RobotStatus of " + status.robot.value);
  }
  written_.insert(status.robot);
  return Status::Ok();
}

Status RobotStatusWriter::Leave(const RobotId& robot) { return Leave(std::vector{robot}); }

Status RobotStatusWriter::Leave(const std::vector<RobotId>& robots) {
  bool disposed = false;
  for (const RobotId& robot : robots) {
    if (written_.erase(robot) == 0) continue;  // never announced: nothing to dispose
    fleetmap_msgs::msg::dds_::RobotStatus_ key;
    key.robot_id(robot.value);
    // HANDLE_NIL: the instance is found from the key (Fast DDS 2.9 lacks lookup_instance).
    if (endpoint_->writer()->dispose(&key, dds::HANDLE_NIL) != ReturnCode_t::RETCODE_OK) {
      return UnavailableError("could not dispose RobotStatus of " + robot.value);
    }
    disposed = true;
  }
  // The process usually exits right after leaving: give the readers a moment to hear it.
  if (disposed) endpoint_->writer()->wait_for_acknowledgments(eprosima::fastrtps::Duration_t(1.0));
  return Status::Ok();
}

int RobotStatusWriter::matched_readers() const {
  dds::PublicationMatchedStatus matched;
  endpoint_->writer()->get_publication_matched_status(matched);
  return matched.current_count;
}

}  // namespace fleetmap::transport
