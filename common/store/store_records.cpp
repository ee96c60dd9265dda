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

constexpr char kFleetKey[] = "fleet";
constexpr char kMapFrameSuffix[] = "/map";

}  // namespace

TileOwner TileOwner::FromKey(const std::string& key) {
  if (key == kFleetKey) return Fleet();
  const size_t suffix = sizeof(kMapFrameSuffix) - 1;
  if (key.size() > suffix && key.compare(key.size() - suffix, suffix, kMapFrameSuffix) == 0) {
    return RobotMapFrame(RobotId{key.substr(0, key.size() - suffix)});
  }
  return Robot(RobotId{key});
}

std::string TileOwner::key() const {
  switch (kind_) {
    case Kind::kFleet:
      return kFleetKey;
    case Kind::kRobot:
      return robot_.value;
    case Kind::kRobotMapFrame:
      return robot_.value + kMapFrameSuffix;
  }
  return robot_.value;
}

std::ostream& operator<<(std::ostream& os, const TileOwner& owner) { return os << owner.key(); }

Status ValidateTileRecord(const TileRecord& record) {
  std::ostringstream where;
  where << "tile record (owner '" << record.owner << "', " << record.tile << ", revision "
        << record.revision << ")";
  // The fleet's rows have no robot; a robot's, in either frame, must name a valid one.
  return CheckOwnerAndStamp(record.owner.is_fleet() ? kFleetKey : record.owner.robot().value,
                            record.stamp_ns, where.str());
}

Status ValidateEvidenceRecord(const EvidenceRecord& record) {
  std::ostringstream where;
  where << "evidence record (robot '" << record.robot.value << "', " << record.tile << ")";
  return CheckOwnerAndStamp(record.robot.value, record.stamp_ns, where.str());
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
