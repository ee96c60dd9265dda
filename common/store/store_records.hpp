#pragma once

#include <cstdint>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "common/core/ids.hpp"
#include "common/core/status.hpp"

namespace fleetmap::store {

// Whose a stored tile row is: the fleet's (fused tiles), a robot's (its tiles in the fleet
// frame, which the fused map is rebuilt from) or a robot's own map frame (the tiles of a robot
// the server places by registration, kept apart). Rows store it as a key: "fleet", "<robot>" or
// "<robot>/map" (the ROS name of that frame).
class TileOwner {
 public:
  enum class Kind : uint8_t { kFleet, kRobot, kRobotMapFrame };

  static TileOwner Fleet() { return TileOwner(Kind::kFleet, RobotId{}); }
  static TileOwner Robot(RobotId robot) { return TileOwner(Kind::kRobot, std::move(robot)); }
  static TileOwner RobotMapFrame(RobotId robot) {
    return TileOwner(Kind::kRobotMapFrame, std::move(robot));
  }
  // The owner a stored key names. Any other key is read as a robot's, whose name the record
  // checks (ValidateTileRecord) refuse when it is not one.
  static TileOwner FromKey(const std::string& key);

  Kind kind() const { return kind_; }
  bool is_fleet() const { return kind_ == Kind::kFleet; }
  // The robot whose tiles these are; empty for the fleet.
  const RobotId& robot() const { return robot_; }
  std::string key() const;

  friend auto operator<=>(const TileOwner&, const TileOwner&) = default;
  friend bool operator==(const TileOwner&, const TileOwner&) = default;

 private:
  TileOwner(Kind kind, RobotId robot) : kind_(kind), robot_(std::move(robot)) {}

  Kind kind_;
  RobotId robot_;
};

std::ostream& operator<<(std::ostream& os, const TileOwner& owner);

// One revision of one tile. The payload is opaque to the store: the server encodes tiles with its
// own codec.
struct TileRecord {
  TileOwner owner = TileOwner::Fleet();
  TileId tile;
  uint32_t revision = 0;  // newer content has a higher revision
  int64_t stamp_ns = 0;   // when this revision was made, ns since the Unix epoch
  std::string payload;

  friend bool operator==(const TileRecord&, const TileRecord&) = default;
};

// One robot's evidence for one tile: what the fusion needs to rebuild that robot's contribution
// exactly (its cells and when each last changed). Opaque to the store, like tile payloads.
struct EvidenceRecord {
  RobotId robot;
  TileId tile;
  int64_t stamp_ns = 0;  // the newest tile revision it reflects, ns since the Unix epoch
  std::string payload;

  friend bool operator==(const EvidenceRecord&, const EvidenceRecord&) = default;
};

// One (owner, tile): the key of tile_latest and tile_evidence rows.
struct TileKey {
  TileOwner owner = TileOwner::Fleet();
  TileId tile;

  friend auto operator<=>(const TileKey&, const TileKey&) = default;
  friend bool operator==(const TileKey&, const TileKey&) = default;
};

// What the server knows about a robot of the fleet.
struct RobotRecord {
  RobotId robot;
  int64_t first_seen_ns = 0;
  int64_t last_seen_ns = 0;
  std::string state;           // "active" | "left" | "lost"
  std::string status_payload;  // opaque: the server's encoding of the robot's last status

  friend bool operator==(const RobotRecord&, const RobotRecord&) = default;
};

// What MapStore::Write commits in one transaction.
struct StoreBatch {
  std::vector<TileRecord> tiles;         // revisions (latest row and history)
  std::vector<EvidenceRecord> evidence;  // replaces each (owner, tile)'s evidence row
  std::vector<TileKey> removed;          // deleted first: latest row, history and evidence
  std::vector<RobotRecord> robots;       // as PutRobot

  bool empty() const {
    return tiles.empty() && evidence.empty() && removed.empty() && robots.empty();
  }
  size_t size() const { return tiles.size() + evidence.size() + removed.size() + robots.size(); }
};

// A finished mapping session: one robot's map of its session, from joining to leaving (or being
// lost). The payload is opaque to the store (the server stores the session's vector map).
struct SessionRecord {
  int64_t id = 0;  // assigned by the store
  RobotId robot;
  int64_t started_ns = 0;
  int64_t ended_ns = 0;
  std::string payload;

  friend bool operator==(const SessionRecord&, const SessionRecord&) = default;
};

// An operator's admission of a robot (`fleetmap admit`): its tiles are fused and it is never
// quarantined, also after the server restarts.
struct AdmissionRecord {
  RobotId robot;
  std::string operator_name;  // who admitted it, as the admission said ("" when it did not)
  int64_t admitted_ns = 0;    // when the server received it

  friend bool operator==(const AdmissionRecord&, const AdmissionRecord&) = default;
};

// OK when `record` may be stored: owner is a valid robot name (kFleetOwner is one) or a
// MapFrameOwner, stamp_ns >= 0.
Status ValidateTileRecord(const TileRecord& record);
// OK when `record` may be stored: owner is a valid robot name, stamp_ns >= 0.
Status ValidateEvidenceRecord(const EvidenceRecord& record);
// OK when `record` may be stored: valid robot name, known state, 0 <= first_seen <= last_seen.
Status ValidateRobotRecord(const RobotRecord& record);
// OK when `record` may be stored: valid robot name, 0 <= started_ns <= ended_ns.
Status ValidateSessionRecord(const SessionRecord& record);

}  // namespace fleetmap::store
