#pragma once

// fleetmap's own types for the entity, sub-map graph and object-model topics. Conversions to the
// wire types are in conversions.hpp; the readers and writers in keyed_state_topic.hpp.

#include <cstdint>
#include <string>
#include <vector>

#include "common/core/ids.hpp"
#include "common/core/robot_status.hpp"
#include "common/core/types.hpp"
#include "common/scene/entities.hpp"
#include "common/scene/patch.hpp"
#include "common/scene/submap_graph.hpp"
#include "common/scene/submap_node.hpp"

namespace fleetmap::transport {

// One entity a robot recognised (rt/fleetmap/entities), in the robot's map frame. The entity's
// own id is the instance key beside the robot's.
struct EntityMessage {
  RobotId robot;
  Timestamp stamp{};
  std::string frame_id = "map";
  scene::Entity entity;

  const std::string& entity_id() const;
};

// One node of the sub-map graph (rt/fleetmap/submap_graph): the plain node the prediction tracker
// makes, under the name the other topics' messages share.
using SubmapMessage = scene::SubmapNode;

// A learned class of movable objects (rt/fleetmap/object_templates).
struct ObjectTemplateMessage {
  uint32_t template_id = 0;
  uint32_t learning_run = 0;
  uint32_t object_count = 0;
  scene::Patch patch;
  Timestamp stamp{};
};

// One sighting of a learned object: in which mapping session, and its pose in the fleet frame.
struct ObjectSighting {
  uint32_t session = 0;
  Pose2 fleet_from_object;
};

// A learned physical object (rt/fleetmap/objects).
struct ObjectModelMessage {
  uint32_t object_id = 0;
  uint32_t learning_run = 0;
  uint32_t template_id = 0;
  scene::Patch patch;
  std::vector<ObjectSighting> sightings;
  Timestamp stamp{};
};

// Where a robot's map frame sits in the fleet frame, as the server knows it
// (rt/fleetmap/robot_frames, one instance per robot).
struct RobotFrameMessage {
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

const char* RobotFrameStateName(RobotFrameMessage::State state);
const char* RobotStandingName(RobotFrameMessage::Standing standing);

// An operator admits a quarantined robot (rt/fleetmap/admissions, `fleetmap admit`).
struct RobotAdmissionMessage {
  RobotId robot;
  Timestamp stamp{};
  std::string operator_name;
};

// A fleetmap-server's word that it is alive (rt/fleetmap/servers, docs/standby.md): written every
// half second; of the live servers the strongest serves.
struct FleetServerMessage {
  std::string server_id;  // its DDS participant's GUID prefix (Participant::id())
  std::string name;       // for people
  int32_t ownership_strength = 0;
  bool serving = false;
  Timestamp started{};
  Timestamp stamp{};
  uint32_t robots = 0;
};

}  // namespace fleetmap::transport
