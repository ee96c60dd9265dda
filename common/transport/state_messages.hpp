#pragma once

// fleetmap's own types for the entity, sub-map graph and object-model topics. Conversions to the
// wire types are in conversions.hpp; the readers and writers in keyed_state_topic.hpp.

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "common/core/ids.hpp"
#include "common/core/robot_frame.hpp"
#include "common/core/robot_status.hpp"
#include "common/core/types.hpp"
#include "common/route_graph/route_graph.hpp"
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

// The fleet map as a route graph (rt/fleetmap/route_graph), one instance per graph_id ("fleet"
// for the fused map's): the graph and its revision, which grows by one at each change.
struct RouteGraphMessage {
  std::string graph_id = "fleet";
  uint64_t revision = 0;
  route_graph::RouteGraph graph;
  Timestamp stamp{};
};

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

// Where a robot's map frame sits in the fleet frame (rt/fleetmap/robot_frames): the fleet map's
// frames table row, as it is (common/core/robot_frame.hpp).
using RobotFrameMessage = RobotFrame;

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
  std::string shard;  // the shard it fuses (docs/shards.md); empty: the whole fleet map
  // The shard's region (fleet frame, metres): min x, min y, max x, max y; zeros without a shard.
  std::array<double, 4> region{};
};

}  // namespace fleetmap::transport
