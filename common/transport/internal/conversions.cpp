#include "common/transport/internal/conversions.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "common/core/number_format.hpp"
namespace fleetmap::transport {
builtin_interfaces::msg::dds_::Time_ ToIdl(Timestamp stamp) {
  const auto since_epoch =
      std::chrono::duration_cast<std::chrono::nanoseconds>(stamp.time_since_epoch());
  const auto seconds = std::chrono::floor<std::chrono::seconds>(since_epoch);
  builtin_interfaces::msg::dds_::Time_ time;
  time.sec(static_cast<int32_t>(seconds.count()));
  time.nanosec(static_cast<uint32_t>((since_epoch - seconds).count()));
  return time;
}

Timestamp FromIdl(const builtin_interfaces::msg::dds_::Time_& time) {
  const auto since_epoch = std::chrono::seconds(time.sec()) +
                           std::chrono::nanoseconds(std::min<uint32_t>(time.nanosec(), 999999999));
  return Timestamp(std::chrono::duration_cast<Clock::duration>(since_epoch));
}

geometry_msgs::msg::dds_::Pose2D_ ToIdl(const Pose2& pose) {
  geometry_msgs::msg::dds_::Pose2D_ out;
  out.x(pose.x);
  out.y(pose.y);
  out.theta(pose.yaw);
  return out;
}

Pose2 FromIdl(const geometry_msgs::msg::dds_::Pose2D_& pose) {
  return {pose.x(), pose.y(), pose.theta()};
}

geometry_msgs::msg::dds_::Pose_ ToIdl3D(const Pose2& pose) {
  geometry_msgs::msg::dds_::Pose_ out;
  out.position().x(pose.x);
  out.position().y(pose.y);
  out.position().z(0.0);
  out.orientation().x(0.0);
  out.orientation().y(0.0);
  out.orientation().z(std::sin(pose.yaw / 2.0));
  out.orientation().w(std::cos(pose.yaw / 2.0));
  return out;
}

StatusOr<Pose2> FromIdl(const geometry_msgs::msg::dds_::Pose_& pose) {
  const auto& q = pose.orientation();
  const double norm = std::sqrt(q.x() * q.x() + q.y() * q.y() + q.z() * q.z() + q.w() * q.w());
  if (!std::isfinite(norm) || std::abs(norm - 1.0) > 1e-3) {
    return InvalidArgumentError("orientation is not a unit quaternion (norm " +
                                std::to_string(norm) + ")");
  }
  if (std::abs(q.x()) > 1e-6 || std::abs(q.y()) > 1e-6) {
    return InvalidArgumentError("orientation is not a rotation about z");
  }
  const Pose2 out{pose.position().x(), pose.position().y(),
                  NormalizeAngle(2.0 * std::atan2(q.z(), q.w()))};
  if (!out.finite()) return InvalidArgumentError("position is not finite");
  return out;
}

nav_msgs::msg::dds_::OccupancyGrid_ ToIdl(const MapMessage& message) {
  nav_msgs::msg::dds_::OccupancyGrid_ out;
  out.header().stamp(ToIdl(message.stamp));
  out.header().frame_id(message.frame_id);
  out.info().map_load_time(ToIdl(message.stamp));
  out.info().resolution(static_cast<float>(message.grid.resolution()));
  out.info().width(static_cast<uint32_t>(message.grid.width()));
  out.info().height(static_cast<uint32_t>(message.grid.height()));
  out.info().origin(ToIdl3D(message.grid.origin()));
  out.data(message.grid.data());
  return out;
}

StatusOr<MapMessage> FromIdl(const nav_msgs::msg::dds_::OccupancyGrid_& message) {
  const auto& info = message.info();
  const uint64_t cells = static_cast<uint64_t>(info.width()) * info.height();
  if (cells != message.data().size()) {
    return InvalidArgumentError("OccupancyGrid says " + std::to_string(info.width()) + " x " +
                                std::to_string(info.height()) + " cells but carries " +
                                std::to_string(message.data().size()));
  }
  if (info.width() > static_cast<uint32_t>(INT32_MAX) ||
      info.height() > static_cast<uint32_t>(INT32_MAX)) {
    return InvalidArgumentError("OccupancyGrid is too large");
  }
  if (!std::isfinite(info.resolution()) || info.resolution() <= 0.0f) {
    return InvalidArgumentError("OccupancyGrid resolution " + std::to_string(info.resolution()) +
                                " is not a positive number");
  }
  StatusOr<Pose2> origin = FromIdl(info.origin());
  if (!origin.ok()) return origin.status().WithContext("OccupancyGrid origin");
  size_t out_of_range = 0;
  for (const int8_t value : message.data()) {
    if (value < -1 || value > 100) ++out_of_range;
  }
  if (out_of_range > 0) {
    return InvalidArgumentError("OccupancyGrid has " + std::to_string(out_of_range) +
                                " cells outside -1..100");
  }
  MapMessage out;
  out.grid = grid::OccupancyGrid(static_cast<int>(info.width()), static_cast<int>(info.height()),
                                 DoubleFromFloat(info.resolution()), *origin);
  out.grid.mutable_data() = message.data();
  out.frame_id = message.header().frame_id();
  out.stamp = FromIdl(message.header().stamp());
  return out;
}

StatusOr<MapUpdate> FromIdl(const map_msgs::msg::dds_::OccupancyGridUpdate_& update) {
  const uint64_t cells = static_cast<uint64_t>(update.width()) * update.height();
  if (cells != update.data().size()) {
    return InvalidArgumentError("OccupancyGridUpdate says " + std::to_string(update.width()) +
                                " x " + std::to_string(update.height()) + " cells but carries " +
                                std::to_string(update.data().size()));
  }
  if (update.width() > static_cast<uint32_t>(INT32_MAX) ||
      update.height() > static_cast<uint32_t>(INT32_MAX)) {
    return InvalidArgumentError("OccupancyGridUpdate is too large");
  }
  for (const int8_t value : update.data()) {
    if (value < -1 || value > 100) {
      return InvalidArgumentError("OccupancyGridUpdate has a cell outside -1..100");
    }
  }
  MapUpdate out;
  out.x = update.x();
  out.y = update.y();
  out.width = static_cast<int>(update.width());
  out.height = static_cast<int>(update.height());
  out.data = update.data();
  out.stamp = FromIdl(update.header().stamp());
  out.frame_id = update.header().frame_id();
  return out;
}

map_msgs::msg::dds_::OccupancyGridUpdate_ ToIdl(const MapUpdate& update) {
  map_msgs::msg::dds_::OccupancyGridUpdate_ out;
  out.header().stamp(ToIdl(update.stamp));
  out.header().frame_id(update.frame_id);
  out.x(update.x);
  out.y(update.y);
  out.width(static_cast<uint32_t>(update.width));
  out.height(static_cast<uint32_t>(update.height));
  out.data(update.data);
  return out;
}

StatusOr<CompressedMapUpdate> FromIdl(
    const fleetmap_msgs::msg::dds_::CompressedGridUpdate_& update) {
  if (update.width() > static_cast<uint32_t>(INT32_MAX) ||
      update.height() > static_cast<uint32_t>(INT32_MAX)) {
    return InvalidArgumentError("CompressedGridUpdate is too large (" +
                                std::to_string(update.width()) + " x " +
                                std::to_string(update.height()) + " cells)");
  }
  CompressedMapUpdate out;
  out.x = update.x();
  out.y = update.y();
  out.width = static_cast<int>(update.width());
  out.height = static_cast<int>(update.height());
  out.compression = update.compression();
  out.raw_size = update.raw_size();
  out.data = update.data();
  out.stamp = FromIdl(update.header().stamp());
  out.frame_id = update.header().frame_id();
  return out;
}

fleetmap_msgs::msg::dds_::CompressedGridUpdate_ ToIdl(const CompressedMapUpdate& update) {
  fleetmap_msgs::msg::dds_::CompressedGridUpdate_ out;
  out.header().stamp(ToIdl(update.stamp));
  out.header().frame_id(update.frame_id);
  out.x(update.x);
  out.y(update.y);
  out.width(static_cast<uint32_t>(update.width));
  out.height(static_cast<uint32_t>(update.height));
  out.compression(update.compression);
  out.raw_size(update.raw_size);
  out.data(update.data);
  return out;
}

fleetmap_msgs::msg::dds_::RobotStatus_ ToIdl(const RobotStatus& status) {
  fleetmap_msgs::msg::dds_::RobotStatus_ out;
  out.robot_id(status.robot.value);
  out.stamp(ToIdl(status.stamp));
  out.map_from_robot(ToIdl(status.map_from_robot));
  out.fleet_from_map(ToIdl(status.fleet_from_map));
  out.map_topic(status.map_topic);
  out.map_width(status.map_width);
  out.map_height(status.map_height);
  out.map_resolution(static_cast<float>(status.map_resolution));
  out.map_revision(status.map_revision);
  out.maps_published(status.maps_published);
  out.tiles_published(status.tiles_published);
  out.bytes_published(status.bytes_published);
  out.sequence_number(status.sequence_number);
  out.baseline_events(status.baselines.events);
  out.baseline_grid_bytes(status.baselines.grid_bytes);
  out.baseline_patch_bytes(status.baselines.patch_bytes);
  out.baseline_zstd3_bytes(status.baselines.zstd3_bytes);
  out.baseline_zstd19_bytes(status.baselines.zstd19_bytes);
  out.baseline_lz4_bytes(status.baselines.lz4_bytes);
  out.baseline_patches_pending(status.baselines.patches_pending);
  out.tiles_in_map_frame(status.tiles_in_map_frame);
  out.fleet_from_map_given(status.fleet_from_map_given);
  return out;
}

StatusOr<RobotStatus> FromIdl(const fleetmap_msgs::msg::dds_::RobotStatus_& status) {
  if (!IsValidRobotName(status.robot_id())) {
    return InvalidArgumentError("RobotStatus robot_id \"" + status.robot_id().substr(0, 80) +
                                "\" is not a valid robot name");
  }
  RobotStatus out;
  out.robot = RobotId{status.robot_id()};
  out.stamp = FromIdl(status.stamp());
  out.map_from_robot = FromIdl(status.map_from_robot());
  out.fleet_from_map = FromIdl(status.fleet_from_map());
  if (!out.map_from_robot.finite() || !out.fleet_from_map.finite()) {
    return InvalidArgumentError("RobotStatus from " + status.robot_id() + " has a non-finite pose");
  }
  out.map_topic = status.map_topic();
  out.map_width = status.map_width();
  out.map_height = status.map_height();
  out.map_resolution = DoubleFromFloat(status.map_resolution());
  out.map_revision = status.map_revision();
  out.maps_published = status.maps_published();
  out.tiles_published = status.tiles_published();
  out.bytes_published = status.bytes_published();
  out.sequence_number = status.sequence_number();
  out.baselines.events = status.baseline_events();
  out.baselines.grid_bytes = status.baseline_grid_bytes();
  out.baselines.patch_bytes = status.baseline_patch_bytes();
  out.baselines.zstd3_bytes = status.baseline_zstd3_bytes();
  out.baselines.zstd19_bytes = status.baseline_zstd19_bytes();
  out.baselines.lz4_bytes = status.baseline_lz4_bytes();
  out.baselines.patches_pending = status.baseline_patches_pending();
  out.tiles_in_map_frame = status.tiles_in_map_frame();
  out.fleet_from_map_given = status.fleet_from_map_given();
  return out;
}

}  // namespace fleetmap::transport
