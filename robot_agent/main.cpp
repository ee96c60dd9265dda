// fleetmap-agent: publishes one robot's map and status to the fleet.
#include <spdlog/cfg/env.h>
#include <spdlog/spdlog.h>
#include <CLI/CLI.hpp>

#include <atomic>
#include <csignal>
#include <vector>

#include "common/config/command_line.hpp"
#include "common/config/fleet_transforms.hpp"
#include "robot_agent/agent_node.hpp"

namespace {

std::atomic<bool> g_stop{false};

void OnSignal(int /*signal*/) { g_stop.store(true); }

fleetmap::Pose2 PoseFrom(const std::vector<double>& values) {
  return {values.at(0), values.at(1), values.at(2)};
}

}  // namespace

int main(int argc, char** argv) {
  // SPDLOG_LEVEL=debug in the environment logs every decision, not only the ones people need.
  spdlog::cfg::load_env_levels();
  CLI::App app{"fleetmap-agent: publishes one robot's map and status to the fleet over DDS"};
  fleetmap::agent::AgentOptions options;
  std::vector<double> fleet_from_map = {0.0, 0.0, 0.0};
  std::vector<double> pose = {0.0, 0.0, 0.0};
  double duration_s = 0.0;
  int domain = 0;  // $FLEETMAP_DOMAIN comes in as --domain (config::DdsEnvironment)
  bool localhost_only = false;
  app.add_option("--robot-id", options.robot.value, "robot name, e.g. alpha")->required();
  auto* map_option = app.add_option(
      "--map", options.map_path,
      "ROS map_server YAML of the robot's map (re-read when it or its image changes)");
  app.add_option("--max-cells", options.map_limits.max_cells,
                 "refuse --map images with more cells than this")
      ->capture_default_str();
  app.add_option("--max-decoded-bytes", options.map_limits.max_decoded_bytes,
                 "refuse --map images that decode to more bytes than this")
      ->capture_default_str();
  // One map source: on the command line, it also drops another one a config file gives.
  auto* topic_option = app.add_option("--ros-topic", options.ros_topic,
                                      "DDS topic with the robot's nav_msgs/OccupancyGrid, e.g. "
                                      "rt/map")
                           ->excludes(map_option);
  app.add_option("--entities", options.entities_path,
                 "entities JSON (doors, stairs, people's tracks) to publish (re-read on change)");
  std::string wire = "tiles";
  app.add_option("--wire", wire,
                 "tiles (vector tiles), or a ROS-native baseline: grid (the whole "
                 "nav_msgs/OccupancyGrid at every change), grid-updates (the grid once, then "
                 "map_msgs/OccupancyGridUpdate per changed tile), grid-updates-zstd (those "
                 "patches zstd -3)")
      ->check(CLI::IsMember({"tiles", "grid", "grid-updates", "grid-updates-zstd"}));
  app.add_flag("--measure-baselines", options.measure_baselines,
               "with --wire tiles: also measure what the same map changes would cost on the grid "
               "wires (reported in the robot's status)");
  std::string sim_kind;
  fleetmap::agent::SimOptions sim;
  app.add_option("--sim", sim_kind,
                 "built-in robot exploring a terrain: office, maze, unstructured, warehouse")
      ->excludes(map_option)
      ->excludes(topic_option);
  app.add_option("--sim-size", sim.size, "simulated terrain side, metres")
      ->check(CLI::PositiveNumber);
  app.add_option("--sim-seed", sim.seed, "simulated terrain seed (the same for the whole fleet)");
  app.add_option("--sim-robot-index", sim.robot_index, "this robot's start among the fleet's");
  app.add_option("--sim-robots", sim.robots, "robots in the simulated fleet");
  app.add_option("--sim-rate", sim.scans_per_second, "simulated laser scans per second")
      ->check(CLI::PositiveNumber);
  std::vector<double> sim_frame = {0.0, 0.0, 0.0};
  app.add_option("--sim-frame", sim_frame,
                 "x y yaw of the simulated robot's map frame in the terrain's frame (a robot "
                 "started at an unknown pose; pair with --unplaced). Only the simulator uses it")
      ->expected(3);
  app.add_option("--tile-size", options.tiles.tile_size, "tile side in metres (fleet frame)")
      ->check(CLI::PositiveNumber);
  app.add_option("--epsilon", options.tiles.epsilon,
                 "vector map error bound, metres (0: sqrt(2) res)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--max-kbps", options.tiles.max_kbps, "bandwidth budget for tiles (0: none)")
      ->check(CLI::NonNegativeNumber);
  auto* fleet_option = app.add_option("--fleet-from-map", fleet_from_map,
                                      "x y yaw of the map frame in the fleet frame")
                           ->expected(3);
  std::string transforms_path;
  app.add_option("--transforms", transforms_path,
                 "YAML of every robot's fleet_from_map (robots: {name: [x, y, yaw]})")
      ->excludes(fleet_option);
  app.add_flag("--unplaced", options.unplaced,
               "the robot's map frame is not known in the fleet: publish tiles in the map frame "
               "and let the server place it by registration (rt/fleetmap/robot_frames)")
      ->excludes(fleet_option)
      ->excludes("--transforms");
  app.add_option("--pose", pose, "x y yaw of the robot in its map frame")->expected(3);
  app.add_option("--duration", duration_s, "seconds to run before leaving (0: until Ctrl-C)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--domain", domain, "DDS domain id (default: $FLEETMAP_DOMAIN, else 0)");
  double claim_wait_s = 1.0;
  app.add_option("--claim-wait", claim_wait_s,
                 "seconds to listen for another agent already using this robot id (0: skip)")
      ->check(CLI::NonNegativeNumber);
  double server_wait_s = 10.0;
  app.add_option("--server-wait", server_wait_s,
                 "seconds without a fleet server in sight before the agent says so")
      ->check(CLI::PositiveNumber);
  std::string security_dir;
  app.add_option("--security", security_dir,
                 "DDS Security folder (fleetmap security enroll): join the secured fleet as the "
                 "identity named after --robot-id");
  app.add_flag("--localhost-only", localhost_only,
               "use UDP on 127.0.0.1 only (also $FLEETMAP_LOCALHOST_ONLY=1)");
  app.add_option("--discovery-server", options.dds.discovery_server,
                 "Fast DDS discovery servers to discover through, IP:PORT[;IP:PORT] (also "
                 "$ROS_DISCOVERY_SERVER; `fastdds discovery -i 0 -l IP -p PORT` starts one)");
  if (const auto exit_now =
          fleetmap::config::ParseFleetProgram(app, argc, argv, "fleetmap_agent")) {
    return *exit_now;
  }

  options.wire = *fleetmap::WireFromName(wire);  // CLI11 checked the name
  if (!sim_kind.empty()) {
    const auto kind = fleetmap::sim::TerrainKindFromName(sim_kind);
    if (!kind) {
      spdlog::error(
          "fleetmap-agent: --sim \"{}\" is not a terrain kind (office, maze, unstructured, "
          "warehouse)",
          sim_kind);
      return 2;
    }
    sim.kind = *kind;
    sim.world_from_map = PoseFrom(sim_frame);
    options.sim = sim;
  }
  options.fleet_from_map = PoseFrom(fleet_from_map);
  if (!transforms_path.empty()) {
    const auto transforms = fleetmap::config::LoadFleetTransforms(transforms_path);
    if (!transforms.ok()) {
      spdlog::error("fleetmap-agent: {}", transforms.status().message());
      return 2;
    }
    const auto mine = transforms->find(options.robot);
    if (mine == transforms->end()) {
      spdlog::error("fleetmap-agent: {}: no entry for robot {}", transforms_path,
                    options.robot.value);
      return 2;
    }
    options.fleet_from_map = mine->second;
  }
  options.map_from_robot = PoseFrom(pose);
  options.claim_wait = std::chrono::milliseconds(static_cast<int64_t>(claim_wait_s * 1000.0));
  options.server_wait = std::chrono::milliseconds(static_cast<int64_t>(server_wait_s * 1000.0));
  options.duration = std::chrono::milliseconds(static_cast<int64_t>(duration_s * 1000.0));
  options.dds.domain_id = domain;
  options.dds.localhost_only = localhost_only;
  if (!security_dir.empty()) {
    if (const auto secured = options.dds.UseSecurityFolder(security_dir, options.robot.value);
        !secured.ok()) {
      spdlog::error("fleetmap-agent: --security: {}", secured.message());
      return 2;
    }
  }

  std::signal(SIGINT, OnSignal);
  std::signal(SIGTERM, OnSignal);

  spdlog::info("fleetmap-agent: options\n{}", fleetmap::DescribeOptions(options));
  auto node = fleetmap::agent::AgentNode::Create(std::move(options));
  if (!node.ok()) {
    spdlog::error("fleetmap-agent: {}", node.status().message());
    return node.status().code() == fleetmap::StatusCode::kUnavailable ? 1 : 2;
  }
  const fleetmap::Status run = (*node)->Run(g_stop);
  // Every exit deletes the DDS participant first (the node owns it): with DDS Security, a
  // participant still alive when the process exits crashes in OpenSSL's teardown.
  node->reset();
  if (!run.ok()) {
    spdlog::error("fleetmap-agent: {}", run.message());
    return 1;
  }
  return 0;
}
