#pragma once

#include <cstdint>
#include <string>

#include "common/core/ids.hpp"
#include "common/core/types.hpp"

namespace fleetmap {

// Where a robot's map frame sits in the fleet frame, as the server knows it: one row of the
// fleet map's frames table (fusion::FleetMap), published as it is on rt/fleetmap/robot_frames
// (one instance per robot).
struct RobotFrame {
  enum class State : uint8_t {
    kUnplaced = 0,  // tiles in the robot's own map frame, not placed yet
    kPlaced = 1,    // registered against the fleet map (or another robot's) and fused
    kRevised = 2,   // placed, then moved because the old placement contradicted the map
    kGiven = 3,     // the transform was given to the agent (--fleet-from-map)
    kAnchor = 4,    // the first robot: its map frame became the fleet frame
  };
  RobotId robot;
  Timestamp stamp{};
  State state = State::kUnplaced;
  Pose2 fleet_from_map;
  double confidence = 0.0;     // in [0, 1]
  double overlap = 0.0;        // share of the robot's known cells on the map it was placed on
  uint32_t placements = 0;     // times the server placed the robot (revisions + 1)
  std::string placed_against;  // "fleet", or the robot whose map it was registered to
  // Whether its tiles are fused (docs/fleet.md, "Quarantine").
  enum class Standing : uint8_t { kTrusted = 0, kQuarantined = 1, kAdmitted = 2 };
  Standing standing = Standing::kTrusted;
  std::string standing_reason;      // for people; empty when trusted
  double contradicted_share = 0.0;  // of the fleet's established walls it sees, called free
  double contradicted_m = 0.0;      // metres of those walls
  // The contradicting area in the fleet frame; min > max when there is none.
  Point2 area_min = Point2::Zero();
  Point2 area_max = Point2(-1.0, -1.0);
  // While unplaced: why the server has not placed it yet (the last registration's verdict).
  std::string waiting_reason;

  // The robot's frame is known: every state but kUnplaced.
  bool placed() const { return state != State::kUnplaced; }
};

const char* RobotFrameStateName(RobotFrame::State state);
const char* RobotStandingName(RobotFrame::Standing standing);

}  // namespace fleetmap
