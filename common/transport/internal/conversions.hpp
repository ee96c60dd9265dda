#pragma once

// ToIdl / FromIdl for the plain ROS messages (time, poses, occupancy grids and their updates,
// robot status): with vector_tile_codec.hpp and state_conversions.hpp the only places where
// generated DDS types meet fleetmap's own. Internal to transport. FromIdl validates everything a
// remote peer could have got wrong, and says what.

#include "builtin_interfaces/msg/Time.h"
#include "common/core/robot_status.hpp"
#include "common/core/status.hpp"
#include "common/transport/map_message.hpp"
#include "common/transport/map_update_codec.hpp"
#include "fleetmap_msgs/msg/CompressedGridUpdate.h"
#include "fleetmap_msgs/msg/RobotStatus.h"
#include "geometry_msgs/msg/Pose.h"
#include "geometry_msgs/msg/Pose2D.h"
#include "map_msgs/msg/OccupancyGridUpdate.h"
#include "nav_msgs/msg/OccupancyGrid.h"

namespace fleetmap::transport {

builtin_interfaces::msg::dds_::Time_ ToIdl(Timestamp stamp);
Timestamp FromIdl(const builtin_interfaces::msg::dds_::Time_& time);

geometry_msgs::msg::dds_::Pose2D_ ToIdl(const Pose2& pose);
Pose2 FromIdl(const geometry_msgs::msg::dds_::Pose2D_& pose);

// A planar pose as a 3D pose (z = 0, rotation about z), and back; FromIdl refuses non-finite
// values and rotations that are not about z.
geometry_msgs::msg::dds_::Pose_ ToIdl3D(const Pose2& pose);
StatusOr<Pose2> FromIdl(const geometry_msgs::msg::dds_::Pose_& pose);

nav_msgs::msg::dds_::OccupancyGrid_ ToIdl(const MapMessage& message);
StatusOr<MapMessage> FromIdl(const nav_msgs::msg::dds_::OccupancyGrid_& message);

StatusOr<MapUpdate> FromIdl(const map_msgs::msg::dds_::OccupancyGridUpdate_& update);
map_msgs::msg::dds_::OccupancyGridUpdate_ ToIdl(const MapUpdate& update);

// Only the rectangle's size is checked here: the payload (compression, raw_size, the cells) is
// DecompressMapUpdate's to judge, on the receiver's own thread.
StatusOr<CompressedMapUpdate> FromIdl(
    const fleetmap_msgs::msg::dds_::CompressedGridUpdate_& update);
fleetmap_msgs::msg::dds_::CompressedGridUpdate_ ToIdl(const CompressedMapUpdate& update);

fleetmap_msgs::msg::dds_::RobotStatus_ ToIdl(const RobotStatus& status);
StatusOr<RobotStatus> FromIdl(const fleetmap_msgs::msg::dds_::RobotStatus_& status);

}  // namespace fleetmap::transport
