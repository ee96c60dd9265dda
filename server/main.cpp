// fleetmap-server: follows the fleet and keeps every robot's latest map.
#include <spdlog/cfg/env.h>
#include <spdlog/spdlog.h>
#include <CLI/CLI.hpp>

#include <atomic>
#include <csignal>

#include "common/config/command_line.hpp"
#include "common/config/fleet_transforms.hpp"
#include "common/config/shard_file.hpp"
#include "server/map_aggregator.hpp"
#include "server/server_node.hpp"

namespace {

std::atomic<bool> g_stop{false};

void OnSignal(int /*signal*/) { g_stop.store(true); }

// `--aggregate`: joins the shards' grids into rt/fleetmap/map (docs/shards.md).
int RunAggregator(const fleetmap::server::ServerOptions& options, const fleetmap::ShardPlan& plan) {
  fleetmap::transport::ParticipantOptions dds = options.dds;
  dds.name = "fleetmap-aggregator";
  auto participant = fleetmap::transport::Participant::Create(dds);
  if (!participant.ok()) {
    spdlog::error("fleetmap-server: {}", participant.status().message());
    return 1;
  }
  auto aggregator = fleetmap::server::MapAggregator::Create(
      **participant, plan, {options.worker.map_period, options.map.fusion.max_grid_cells});
  if (!aggregator.ok()) {
    spdlog::error("fleetmap-server: {}", aggregator.status().message());
    return 1;
  }
  const fleetmap::Status run = (*aggregator)->Run(g_stop, options.duration);
  aggregator->reset();  // the readers go before their participant
  participant->reset();
  return run.ok() ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  // SPDLOG_LEVEL=debug in the environment logs every decision, not only the ones people need.
  spdlog::cfg::load_env_levels();
  CLI::App app{
      "fleetmap-server: follows the robot fleet over DDS, fuses its maps, learns the objects "
      "that move and predicts the space behind doors and up stairs"};
  fleetmap::server::ServerOptions options;
  double duration_s = 0.0;
  int domain = 0;  // $FLEETMAP_DOMAIN comes in as --domain (config::DdsEnvironment)
  bool localhost_only = false;
  app.add_option("--duration", duration_s, "seconds to run (0: until Ctrl-C)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--domain", domain, "DDS domain id (default: $FLEETMAP_DOMAIN, else 0)");
  app.add_option("--store", options.worker.store_path,
                 "SQLite map store: the fused map survives restarts (empty: keep nothing)");
  app.add_option("--history-rows", options.worker.history_rows,
                 "tile revisions kept in the store's history (0: all)")
      ->check(CLI::NonNegativeNumber);
  double store_lock_timeout_s = 10.0;
  app.add_option("--store-lock-timeout", store_lock_timeout_s,
                 "seconds to wait for a store another server holds (a restart while the old "
                 "server closes) before exiting with code 2")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  std::string transforms_path;
  app.add_option("--transforms", transforms_path,
                 "YAML of known fleet_from_map transforms (robots: {name: [x, y, yaw]})");
  app.add_option("--tile-size", options.map.fusion.tile_size, "fleet tile side, metres")
      ->check(CLI::PositiveNumber);
  app.add_option("--resolution", options.map.fusion.resolution, "fused grid cell size, metres")
      ->check(CLI::PositiveNumber);
  double map_period_s = 1.0;
  app.add_option("--map-period", map_period_s,
                 "at most one fused grid on rt/fleetmap/map per this many seconds")
      ->check(CLI::PositiveNumber);
  bool no_learning = false;
  app.add_flag("--no-object-learning", no_learning,
               "do not learn movable objects from finished mapping sessions");
  app.add_option("--learn-sessions", options.learning.max_sessions,
                 "object learning uses at most this many newest finished sessions")
      ->check(CLI::PositiveNumber);
  app.add_option("--learn-memory-budget", options.learning.memory_budget_mb,
                 "memory one object-learning run may use, MB (past it, it degrades and warns)")
      ->check(CLI::PositiveNumber);
  bool no_quarantine = false;
  app.add_flag("--no-quarantine", no_quarantine,
               "fuse every robot's tiles, newer evidence winning, even where they contradict what "
               "other robots established (docs/fleet.md, Quarantine)");
  bool no_prediction = false;
  app.add_flag("--no-extrapolation", no_prediction,
               "do not predict sub-maps from the entities robots publish");
  app.add_option("--pth", options.prediction.extrapolation.p_th,
                 "extrapolation threshold on the peak-normalised kernels, in (0, 1)");
  app.add_option("--confirm-precision", options.prediction.confirm_precision,
                 "a judged prediction is confirmed at this observed precision, else retracted");
  app.add_flag("--route-graph", options.route_graph.enabled,
               "publish the fused map as a route graph on rt/fleetmap/route_graph "
               "(docs/route-graph.md)");
  app.add_option("--route-graph-radius", options.route_graph.graph.robot_radius,
                 "the robots' radius the route graph is built for, metres")
      ->capture_default_str();
  app.add_option("--max-tiles-per-robot", options.map.admission.max_tiles_per_robot,
                 "distinct tiles one robot id may hold (about 250 KB of server memory each)")
      ->check(CLI::PositiveNumber);
  double max_clock_ahead_s = 30.0;
  app.add_option("--max-clock-ahead", max_clock_ahead_s,
                 "refuse tiles stamped more than this many seconds ahead of the server's clock")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--max-bytes-per-second", options.map.admission.max_bytes_per_second,
                 "sustained tile bytes per second one robot may send")
      ->check(CLI::PositiveNumber);
  app.add_option("--max-vertices-per-tile", options.map.admission.budget.max_vertices_per_tile,
                 "vertices one robot tile may decode to (refused before it is inflated)")
      ->check(CLI::PositiveNumber);
  app.add_option("--max-vertices-per-robot", options.map.admission.budget.max_vertices_per_robot,
                 "vertices all of one robot id's tiles may hold")
      ->check(CLI::PositiveNumber);
  double max_memory_mb = static_cast<double>(options.map.admission.budget.max_memory_bytes >> 20);
  app.add_option("--max-tile-memory", max_memory_mb,
                 "MB all robots' tiles may hold, decoded; past it the robots claimed last give way")
      ->check(CLI::PositiveNumber);
  double max_robot_mb = static_cast<double>(options.map.admission.budget.max_bytes_per_robot >> 20);
  app.add_option("--max-robot-memory", max_robot_mb,
                 "MB one robot id's tiles may hold, decoded (a participant's ids: 2 robots' worth)")
      ->check(CLI::PositiveNumber);
  app.add_option("--max-painted-tiles-per-second",
                 options.map.admission.budget.max_painted_tiles_per_second,
                 "tiles' worth of cells one participant's tiles may paint a second, sustained")
      ->check(CLI::PositiveNumber);
  app.add_option("--max-robots-per-participant", options.max_robots_per_participant,
                 "robot ids one DDS participant may speak for")
      ->check(CLI::PositiveNumber);
  app.add_option("--max-map-cells", options.map.fusion.max_grid_cells,
                 "cells of the one grid on rt/fleetmap/map (the fused tiles carry everything)")
      ->check(CLI::PositiveNumber);
  app.add_option("--placement-confidence", options.map.placement.registration.min_confidence,
                 "least registration confidence that places a robot started with --unplaced")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  app.add_option("--placement-max-drift", options.map.placement.registration.max_drift_per_m,
                 "verify placements allowing each 3 m block of a robot's map to shift by this "
                 "much per metre from where the maps agree (SLAM drift; 0: rigid; 0.03 by default; "
                 "docs/registration.md, Drift)")
      ->check(CLI::Range(0.0, 0.2))
      ->capture_default_str();
  app.add_option("--placement-sequential-wins", options.map.placement.sequential_wins,
                 "also place a robot when this many registrations in a row of its grown map "
                 "found the same placement verified at --placement-sequential-confidence or "
                 "more, under the bar (0: only at the bar; docs/registration.md, Evidence over "
                 "time)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  app.add_option("--placement-sequential-confidence", options.map.placement.sequential_confidence,
                 "least confidence of a verified placement that counts as one of those wins")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  double check_period_s = 5.0;
  app.add_option("--placement-check-period", check_period_s,
                 "a placed robot's placement is checked against the rest of the fleet at most "
                 "this often, in seconds, once its map changed (a contradiction revises it)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--ownership-strength", options.ownership_strength,
                 "of the live servers on the domain the strongest serves the fleet; start a hot "
                 "standby with a lower strength (docs/standby.md)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  app.add_option("--name", options.name,
                 "how other servers, the web view and the log name this server (default: "
                 "host:pid)");
  std::string shard_name;
  app.add_option("--shard", shard_name,
                 "fuse one shard of the fleet map: this shard's region only (--region, or its "
                 "entry in --shards); its grid goes on rt/fleetmap/<shard>/map (docs/shards.md)");
  std::vector<double> region;
  app.add_option("--region", region,
                 "the shard's region: X0 Y0 X1 Y1, metres in the fleet frame (a tile is the "
                 "shard's when its centre lies inside)")
      ->expected(4);
  std::string shards_path;
  app.add_option("--shards", shards_path,
                 "YAML of every shard's region (shards: {name: [X0, Y0, X1, Y1]}): with --shard, "
                 "tiles on no shard's region are reported; with --aggregate, the shards to join");
  bool aggregate = false;
  app.add_flag("--aggregate", aggregate,
               "join the shards' grids (--shards) into rt/fleetmap/map; fuses nothing itself");
  std::string security_dir;
  app.add_option("--security", security_dir,
                 "DDS Security folder (fleetmap security init): join the secured fleet as "
                 "identity \"server\"");
  app.add_flag("--localhost-only", localhost_only,
               "use UDP on 127.0.0.1 only (also $FLEETMAP_LOCALHOST_ONLY=1)");
  app.add_option("--discovery-server", options.dds.discovery_server,
                 "Fast DDS discovery servers to discover through, IP:PORT[;IP:PORT] (also "
                 "$ROS_DISCOVERY_SERVER; `fastdds discovery -i 0 -l IP -p PORT` starts one)");
  if (const auto exit_now =
          fleetmap::config::ParseFleetProgram(app, argc, argv, "fleetmap_server")) {
    return *exit_now;
  }

  options.map.placement.check_period =
      std::chrono::milliseconds(static_cast<int64_t>(check_period_s * 1000.0));

  options.duration = std::chrono::milliseconds(static_cast<int64_t>(duration_s * 1000.0));
  options.map.admission.max_clock_ahead =
      std::chrono::milliseconds(static_cast<int64_t>(max_clock_ahead_s * 1000.0));
  options.worker.store_lock_timeout =
      std::chrono::milliseconds(static_cast<int64_t>(store_lock_timeout_s * 1000.0));
  options.map.admission.budget.max_memory_bytes = static_cast<uint64_t>(max_memory_mb * (1 << 20));
  options.map.admission.budget.max_bytes_per_robot =
      static_cast<uint64_t>(max_robot_mb * (1 << 20));
  options.worker.map_period =
      std::chrono::milliseconds(static_cast<int64_t>(map_period_s * 1000.0));
  options.dds.domain_id = domain;
  if (!transforms_path.empty()) {
    auto transforms = fleetmap::config::LoadFleetTransforms(transforms_path);
    if (!transforms.ok()) {
      spdlog::error("fleetmap-server: {}", transforms.status().message());
      return 2;
    }
    options.transforms = std::move(transforms).value();
  }
  const auto fail = [](const std::string& message) {
    spdlog::error("fleetmap-server: {}", message);
    return 2;
  };
  std::optional<fleetmap::ShardPlan> shard_plan;
  if (!shards_path.empty()) {
    auto plan = fleetmap::config::LoadShardPlan(shards_path);
    if (!plan.ok()) return fail("--shards " + plan.status().message());
    shard_plan = std::move(plan).value();
  }
  if (!region.empty()) {
    if (shard_name.empty()) return fail("--region needs --shard NAME (docs/shards.md)");
    if (shard_plan) return fail("give a shard's region by --region or in --shards, not both");
    auto plan = fleetmap::ShardPlan::Create(
        {fleetmap::ShardRegion{shard_name, region[0], region[1], region[2], region[3]}});
    if (!plan.ok()) return fail("--region: " + plan.status().message());
    shard_plan = std::move(plan).value();
  }
  if (aggregate && (!shard_plan || !shard_name.empty() || !region.empty())) {
    return fail("--aggregate needs --shards FILE (and no --shard or --region)");
  }
  if (!shard_name.empty()) {
    if (!shard_plan)
      return fail("--shard " + shard_name + " needs --region X0 Y0 X1 Y1 or --shards FILE");
    if (shard_plan->Find(shard_name) == nullptr) {
      std::string listed;
      for (const auto& entry : shard_plan->regions())
        listed += (listed.empty() ? "" : ", ") + entry.name;
      return fail("--shard " + shard_name + " is not in " + shards_path + " (it lists " + listed +
                  ")");
    }
    options.shard = fleetmap::ShardAssignment{*shard_plan, shard_name};
  }
  options.dds.localhost_only = localhost_only;
  if (!security_dir.empty()) {
    if (const auto secured = options.dds.UseSecurityFolder(security_dir, "server"); !secured.ok()) {
      spdlog::error("fleetmap-server: --security: {}", secured.message());
      return 2;
    }
  }
  options.learning.enabled = !no_learning;
  options.prediction.enabled = !no_prediction;
  options.map.fusion.quarantine.enabled = !no_quarantine;

  std::signal(SIGINT, OnSignal);
  std::signal(SIGTERM, OnSignal);
  if (aggregate) return RunAggregator(options, *shard_plan);

  spdlog::info("fleetmap-server: options\n{}", fleetmap::DescribeOptions(options));
  auto node = fleetmap::server::ServerNode::Create(std::move(options));
  if (!node.ok()) {
    spdlog::error("fleetmap-server: {}", node.status().message());
    return node.status().code() == fleetmap::StatusCode::kUnavailable ? 1 : 2;
  }
  const fleetmap::Status run = (*node)->Run(g_stop);
  // Every exit deletes the DDS participant first (the node owns it): with DDS Security, a
  // participant still alive when the process exits crashes in OpenSSL's teardown.
  node->reset();
  if (!run.ok()) {
    spdlog::error("fleetmap-server: {}", run.message());
    return 1;
  }
  return 0;
}
