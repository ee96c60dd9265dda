#pragma once

// ToIdl / FromIdl: the only place where generated DDS types meet fleetmap's own. Internal to
// transport. FromIdl validates everything a remote peer could have got wrong, and says what.

#include "builtin_interfaces/msg/Time.h"
#include "common/core/robot_status.hpp"
#include "common/core/status.hpp"
#include "common/transport/map_message.hpp"
#include "common/transport/vector_tile_message.hpp"
#include "common/vector_map/tiled_vector_map.hpp"
#include "fleetmap_msgs/msg/RobotStatus.h"
#include "fleetmap_msgs/msg/VectorTile.h"
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

fleetmap_msgs::msg::dds_::RobotStatus_ ToIdl(const RobotStatus& status);
StatusOr<RobotStatus> FromIdl(const fleetmap_msgs::msg::dds_::RobotStatus_& status);

// Quantises the tile's geometry to int16 multiples of TileQuantum(tile_size) from the tile's
// corner (the layout is in docs/file-formats.md). One-vertex polylines go to the point arrays; a
// closed polyline repeats its first vertex at its end; a polyline of more than 65535 wire vertices
// is split into open pieces that share their end vertices. Fails (kInvalidArgument) when a vertex
// is too far outside its tile for int16, when a coordinate or the tile size is not finite, when a
// half width does not fit, or when a free ring has more than 65535 vertices or a free polygon
// more than 65535 rings.
StatusOr<fleetmap_msgs::msg::dds_::VectorTile_> ToIdl(const VectorTileMessage& message);
// Checks that every count adds up and every number is sane before building the tile. The map
// comes back as it was given to ToIdl, except that obstacles come in the order polylines, then
// point obstacles; a closed polyline of fewer than 3 vertices comes back open, and an open one of
// n >= 4 vertices whose last vertex is its first comes back closed without that last vertex
// (the same segments either way); split polylines come back as their pieces.
StatusOr<VectorTileMessage> FromIdl(const fleetmap_msgs::msg::dds_::VectorTile_& tile);

}  // namespace fleetmap::transport
