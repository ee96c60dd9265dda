#include "common/store/store_records.hpp"

#include <sstream>

namespace fleetmap::store {

namespace {

// Refuses a row whose owner is not a robot name or whose stamp is negative; `where` names it.
Status CheckOwnerAndStamp(const std::string& owner, int64_t stamp_ns, const std::string& where) {
  std::ostringstream what;
  if (!IsValidRobotName(owner)) {
    what << "owner '" << owner
         << "' is not a valid robot name ([A-Za-z][A-Za-z0-9_]*, at most 64 chars)";
  } else if (stamp_ns < 0) {
    what << "stamp_ns " << stamp_ns << " is negative";
  } else {
    return Status::Ok();
  }
  return InvalidArgumentError(where + ": " + what.str());
}

constexpr char kMapFrameSuffix[] = "/map";

}  // namespace

std::string MapFrameOwner(const RobotId& robot) { return robot.value + kMapFrameSuffix; }

std::optional<RobotId> MapFrameRobot(const std::string& owner) {
  const size_t suffix = sizeof(kMapFrameSuffix) - 1;
  if (owner.size() <= suffix || owner.compare(owner.size() - suffix, suffix, kMapFrameSuffix)) {
    return std::nullopt;
  }
  RobotId robot{owner.substr(0, owner.size() - suffix)};
  if (!IsValidRobotName(robot.value)) return std::nullopt;
  return robot;
}

Status ValidateTileRecord(const TileRecord& record) {
  std::ostringstream where;
  where << "tile record (owner '" << record.owner << "', " << record.tile << ", revision "
        << record.revision << ")";
  // A robot's map-frame tiles are its own: the robot's name must be valid.
  const std::optional<RobotId> map_frame = MapFrameRobot(record.owner);
  return CheckOwnerAndStamp(map_frame ? map_frame->value : record.owner, record.stamp_ns,
                            where.str());
}

Status ValidateEvidenceRecord(const EvidenceRecord& record) {
  std::ostringstream where;
  where << "evidence record (owner '" << record.owner << "', " << record.tile << ")";
  return CheckOwnerAndStamp(record.owner, record.stamp_ns, where.str());
}

Status ValidateRobotRecord(const RobotRecord& record) {
  std::ostringstream what;
  if (!IsValidRobotName(record.robot.value)) {
    what << "'" << record.robot.value
         << "' is not a valid robot name ([A-Za-z][A-Za-z0-9_]*, at most 64 chars)";
  } else if (record.state != "active" && record.state != "left" && record.state != "lost") {
    what << "state '" << record.state << "' is not one of active, left, lost";
  } else if (record.first_seen_ns < 0 || record.last_seen_ns < record.first_seen_ns) {
    what << "first_seen_ns " << record.first_seen_ns << " and last_seen_ns " << record.last_seen_ns
         << " do not satisfy 0 <= first_seen_ns <= last_seen_ns";
  } else {
    return Status::Ok();
  }
  return InvalidArgumentError("robot record '" + record.robot.value + "': " + what.str());
}

Status ValidateSessionRecord(const SessionRecord& record) {
  std::ostringstream what;
  if (!IsValidRobotName(record.robot.value)) {
    what << "'" << record.robot.value
         << "' is not a valid robot name ([A-Za-z][A-Za-z0-9_]*, at most 64 chars)";
  } else if (record.started_ns < 0 || record.ended_ns < record.started_ns) {
    what << "started_ns " << record.started_ns << " and ended_ns " << record.ended_ns
         << " do not satisfy 0 <= started_ns <= ended_ns";
  } else {
    return Status::Ok();
  }
  return InvalidArgumentError("session of '" + record.robot.value + "': " + what.str());
}

}  // namespace fleetmap::store
