#pragma once

// One QoS definition per topic, shared by its writer and reader so the two always match.
// Internal to transport: the nodes never see Fast DDS types. docs/topics.md mirrors this file.

#include <chrono>
#include <fastdds/dds/publisher/qos/DataWriterQos.hpp>
#include <fastdds/dds/subscriber/qos/DataReaderQos.hpp>

#include "common/transport/robot_status_reader.hpp"
#include "common/transport/served_state.hpp"

namespace fleetmap::transport {

struct EndpointQos {
  eprosima::fastdds::dds::DataWriterQos writer;
  eprosima::fastdds::dds::DataReaderQos reader;
};

// rt/fleetmap/robot_status: reliable, transient local, keep last 1 per robot, no instance limit,
// manual-by-topic liveliness with a 2 s lease (each status sample renews it), so a dead or
// hung agent is noticed in about 2 s. Agents must write their status more often than the lease.
// Every reliable topic uses the same heartbeat and NACK timings, tuned for lossy Wi-Fi.
EndpointQos RobotStatusQos();

// rt/<robot>/map and rt/fleetmap/map: what nav2's map_server uses for /map (reliable, transient
// local, keep last 1), published asynchronously since a grid is often larger than one datagram.
EndpointQos OccupancyGridQos();

// rt/<map>_updates (map_msgs/OccupancyGridUpdate): reliable, volatile, keep last 16, as ROS 2
// SLAM nodes publish their incremental map updates. The agents' patch wires use it too, for
// rt/<robot>/map_updates and rt/<robot>/map_updates_zstd (fleetmap_msgs/CompressedGridUpdate).
EndpointQos OccupancyGridUpdateQos();

// rt/fleetmap/robot_tiles and rt/fleetmap/fused_tiles: reliable, transient local, keep last 1
// per tile instance, no instance limit (a map has thousands of tiles).
EndpointQos VectorTileQos();

// rt/fleetmap/entities, rt/fleetmap/submap_graph, rt/fleetmap/object_templates,
// rt/fleetmap/objects and rt/fleetmap/robot_frames: state topics like the tiles (reliable,
// transient local, keep last 1 per instance, no instance limit), so a late joiner gets the current
// entities, graph and models.
EndpointQos KeyedStateQos();

// rt/fleetmap/fused_tiles, robot_frames, submap_graph, object_templates and objects, the state a
// server serves (docs/standby.md): KeyedStateQos with EXCLUSIVE ownership, so that readers take
// each instance from the strongest live server only. The writers, of `strength`, offer
// MANUAL_BY_TOPIC liveliness with a kServedLivelinessLease (transport asserts it:
// internal/served_writers.hpp); the readers request that kind and lease, so they leave a dead
// server for the next within about a second.
EndpointQos ServedStateQos(int32_t strength = 0);

// rt/tf: ROS 2's /tf QoS (reliable, volatile, keep last 100), so tf2 listeners (RViz) match.
EndpointQos TfQos();

}  // namespace fleetmap::transport
