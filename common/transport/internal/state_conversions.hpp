#pragma once

// ToIdl / FromIdl for the entity, sub-map and object-model topics (see state_messages.hpp).
// Internal to transport. FromIdl refuses, with a message saying what is wrong, everything a
// remote peer could have got wrong: counts that do not add up, non-finite numbers, ids that are
// not names, a door of zero width, grids larger than their header says.

#include "common/core/status.hpp"
#include "common/transport/state_messages.hpp"
#include "fleetmap_msgs/msg/Entity.h"
#include "fleetmap_msgs/msg/FleetServer.h"
#include "fleetmap_msgs/msg/ObjectModel.h"
#include "fleetmap_msgs/msg/ObjectTemplate.h"
#include "fleetmap_msgs/msg/RobotAdmission.h"
#include "fleetmap_msgs/msg/RobotFrame.h"
#include "fleetmap_msgs/msg/RouteGraph.h"
#include "fleetmap_msgs/msg/Submap.h"

namespace fleetmap::transport {

// Wire values of Entity_::entity_class.
inline constexpr uint8_t kEntityDoor = 1;
inline constexpr uint8_t kEntityStairs = 2;
inline constexpr uint8_t kEntityPerson = 3;

StatusOr<fleetmap_msgs::msg::dds_::Entity_> ToIdl(const EntityMessage& message);
StatusOr<EntityMessage> FromIdl(const fleetmap_msgs::msg::dds_::Entity_& entity);

StatusOr<fleetmap_msgs::msg::dds_::Submap_> ToIdl(const SubmapMessage& message);
StatusOr<SubmapMessage> FromIdl(const fleetmap_msgs::msg::dds_::Submap_& submap);

StatusOr<fleetmap_msgs::msg::dds_::ObjectTemplate_> ToIdl(const ObjectTemplateMessage& message);
StatusOr<ObjectTemplateMessage> FromIdl(const fleetmap_msgs::msg::dds_::ObjectTemplate_& sample);

StatusOr<fleetmap_msgs::msg::dds_::ObjectModel_> ToIdl(const ObjectModelMessage& message);
StatusOr<ObjectModelMessage> FromIdl(const fleetmap_msgs::msg::dds_::ObjectModel_& sample);
StatusOr<fleetmap_msgs::msg::dds_::RouteGraph_> ToIdl(const RouteGraphMessage& message);
StatusOr<RouteGraphMessage> FromIdl(const fleetmap_msgs::msg::dds_::RouteGraph_& sample);

StatusOr<fleetmap_msgs::msg::dds_::RobotFrame_> ToIdl(const RobotFrameMessage& message);
StatusOr<RobotFrameMessage> FromIdl(const fleetmap_msgs::msg::dds_::RobotFrame_& sample);
StatusOr<fleetmap_msgs::msg::dds_::RobotAdmission_> ToIdl(const RobotAdmissionMessage& message);
StatusOr<RobotAdmissionMessage> FromIdl(const fleetmap_msgs::msg::dds_::RobotAdmission_& sample);
StatusOr<fleetmap_msgs::msg::dds_::FleetServer_> ToIdl(const FleetServerMessage& message);
StatusOr<FleetServerMessage> FromIdl(const fleetmap_msgs::msg::dds_::FleetServer_& sample);

}  // namespace fleetmap::transport
