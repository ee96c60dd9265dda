#include "bench/fleet/sim_command.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <iostream>
#include <memory>

#include "bench/fleet/fleet_scenario.hpp"
#include "bench/fleet/fleet_sim.hpp"
#include "bench/fleet/fleet_sim_report.hpp"
#include "bench/fleet/security_report.hpp"
#include "cli/inputs/exit_codes.hpp"
#include "common/core/progress_line.hpp"
#include "common/process/lossy_network_namespace.hpp"
#include "common/sim/terrain_generator.hpp"

namespace fleetmap::bench {
namespace {

struct SimArgs {
  int robots = FleetSimOptions{}.robots;
  FleetScenarioArgs scenario{.size = FleetSimOptions{}.size,
                             .seed = FleetSimOptions{}.seed,
                             .rate = FleetSimOptions{}.scans_per_second};
  std::string out_dir = "out/sim";
  bool compare = true;
  std::string compare_wire = "grid-updates-zstd";
  bool unknown_poses = false;
  bool compare_known = false;
  bool secure = false;
  int view_port = -1;
  std::string params_file;
  int shards = 0;
};

int RunSim(const SimArgs& args) {
  const auto kind = sim::TerrainKindFromName(args.scenario.terrain);
  if (!kind) {
    std::cerr << "fleetmap sim: --terrain \"" << args.scenario.terrain
              << "\" is not a terrain kind (office, maze, unstructured, warehouse)\n";
    return cli::kExitBadInput;
  }
  FleetSimOptions fleet = ScenarioFleetOptions(*kind, args.scenario);
  fleet.robots = args.robots;
  fleet.view_port = args.view_port;
  fleet.params_file = args.params_file;
  fleet.shards = args.shards;
  if (args.unknown_poses) fleet.sim_frames = UnknownPoseFrames(fleet.seed, fleet.robots);
  if (const Status valid = fleet.Validate(); !valid.ok()) {
    std::cerr << "fleetmap sim: " << valid.message() << "\n";
    return cli::kExitBadInput;
  }
  if (args.secure) {
    // The run's own credentials, made afresh in the report folder (docs/security.md).
    fleet.security_dir = (std::filesystem::path(args.out_dir) / "security").string();
    std::error_code error;
    std::filesystem::remove_all(fleet.security_dir, error);
    if (const Status made = MakeSimSecurityFolder(fleet.security_dir, fleet.robots); !made.ok()) {
      std::cerr << "fleetmap sim: " << made.message() << "\n";
      return cli::kExitBadInput;
    }
  }
  // The ground truth the report scores against: the same seeded terrain the agents explore.
  grid::OccupancyGrid truth;
  if (const int code = PrepareFleetRuns("fleetmap sim", &fleet, &truth); code != cli::kExitOk) {
    return code;
  }

  // Robots at unknown poses run on the tile wire only and do not measure the grid wires (the
  // placement is what is measured); --compare-known runs them again in one shared frame.
  // --secure runs the tile wire secured, then the same without security, unmeasured; where this
  // process may (root), each in a network namespace of its own, so that the loopback bytes
  // counted are the fleet's alone.
  // A machine may allow root but not namespaces (a container): a first namespace made and removed
  // here tells.
  // With --view the fleet stays in this namespace, where the browser can reach the page.
  const bool isolated =
      args.secure && args.view_port < 0 && process::LossyNetworkNamespace::Create(0).ok();
  const auto run = [&](const std::string& wire, const std::vector<Pose2>& sim_frames,
                       bool secured = true) -> StatusOr<FleetRunResult> {
    FleetSimOptions options = fleet;
    options.wire = wire;
    options.sim_frames = sim_frames;
    options.measure_baselines = wire == "tiles" && !args.unknown_poses && !args.secure;
    if (!secured) options.security_dir.clear();
    std::string label = args.unknown_poses ? (sim_frames.empty() ? "known poses" : "unknown poses")
                                           : wire + " wire";
    if (args.secure) label += secured ? ", secured" : ", no security";
    std::unique_ptr<process::LossyNetworkNamespace> network;
    std::unique_ptr<process::LossyNetworkNamespace::Inside> inside;
    if (isolated) {
      FLEETMAP_ASSIGN_OR_RETURN(network, process::LossyNetworkNamespace::Create(0));
      FLEETMAP_ASSIGN_OR_RETURN(inside, network->Enter());
    }
    ProgressLine progress = ProgressLine::OnStderr();
    StatusOr<FleetRunResult> result = RunFleet(options, [&](double seconds) {
      progress.Update(
          seconds < 0
              ? fmt::format("[{}] the agents finish measuring the grid wires", label)
              : fmt::format("[{}] {:.0f} / {:.0f} s", label, seconds, args.scenario.duration_s));
    });
    progress.Finish();
    return result;
  };
  StatusOr<FleetRunResult> tiles = run("tiles", fleet.sim_frames);
  if (!tiles.ok()) {
    std::cerr << "fleetmap sim: " << tiles.status().message() << "\n";
    return 1;
  }
  std::optional<FleetRunResult> known_poses;
  if (args.unknown_poses && args.compare_known) {
    StatusOr<FleetRunResult> known_run = run("tiles", {});
    if (!known_run.ok()) {
      std::cerr << "fleetmap sim: the known-pose run failed: " << known_run.status().message()
                << "\n";
      return 1;
    }
    known_poses = std::move(known_run).value();
  }
  std::optional<std::string> security_table;
  if (args.secure) {
    StatusOr<FleetRunResult> plain = run("tiles", fleet.sim_frames, /*secured=*/false);
    if (!plain.ok()) {
      std::cerr << "fleetmap sim: the run without security failed: " << plain.status().message()
                << "\n";
      return 1;
    }
    StatusOr<std::string> table = WriteSecurityComparison(*tiles, *plain, isolated, args.out_dir);
    if (!table.ok()) {
      std::cerr << "fleetmap sim: " << table.status().message() << "\n";
      return 1;
    }
    security_table = std::move(table).value();
  }
  std::optional<FleetRunResult> compared;
  if (args.compare && !args.unknown_poses && !args.secure && args.shards == 0) {
    StatusOr<FleetRunResult> compared_run = run(args.compare_wire, {});
    if (!compared_run.ok()) {
      std::cerr << "fleetmap sim: the " << args.compare_wire
                << " run failed: " << compared_run.status().message() << "\n";
      return 1;
    }
    compared = std::move(compared_run).value();
  }
  StatusOr<std::string> summary =
      WriteFleetReport(fleet, *tiles, compared, truth, args.out_dir, known_poses);
  if (!summary.ok()) {
    std::cerr << "fleetmap sim: " << summary.status().message() << "\n";
    return 1;
  }
  std::cout << *summary << "\n";
  if (security_table) std::cout << "\n" << *security_table;
  return cli::kExitOk;
}

}  // namespace

void AddSimCommand(CLI::App& app, int* exit_code) {
  auto args = std::make_shared<SimArgs>();
  CLI::App* command = app.add_subcommand(
      "sim", "Run a simulated fleet (server + N agent processes over DDS on loopback) and report");
  command->add_option("--robots", args->robots, "robots (1..64)");
  AddFleetScenarioOptions(command, &args->scenario);
  command->add_option("--out", args->out_dir, "report folder");
  command->add_flag("!--no-compare", args->compare,
                    "skip the same run on a grid wire (--compare-wire) for real");
  command
      ->add_option("--compare-wire", args->compare_wire,
                   "the grid wire of the second run: grid, grid-updates or grid-updates-zstd")
      ->check(CLI::IsMember({"grid", "grid-updates", "grid-updates-zstd"}))
      ->capture_default_str();
  command->add_flag("--unknown-poses", args->unknown_poses,
                    "robots start at unknown poses: each maps in its own frame (a seeded random "
                    "rigid transform of the terrain's), runs --unplaced and is placed by the "
                    "server; reports each placement against the truth (tile wire only, no "
                    "grid-wire run)");
  command
      ->add_flag("--compare-known", args->compare_known,
                 "with --unknown-poses: run the same scenario with known poses too and compare "
                 "the fused maps")
      ->needs("--unknown-poses");
  command->add_flag("--secure", args->secure,
                    "run the fleet with DDS Security (credentials made in <out>/security), then "
                    "the same run without it, and compare join times, wire bytes and latency "
                    "(no grid-wire run)");
  command
      ->add_option("--view", args->view_port,
                   "serve the live web view at http://127.0.0.1:PORT/ while the fleet runs "
                   "(fleetmap view; each run of the sim in turn)")
      ->check(CLI::Range(1, 65535));
  command->add_option("--shards", args->shards,
                      "fuse on K shard servers, each a strip of the terrain, joined by the "
                      "aggregator, and compare with one server fusing everything in the same run "
                      "(docs/shards.md; 2..8, tile wire, no grid-wire run)");
  command->add_option("--params", args->params_file,
                      "a ROS 2 params file with fleetmap_server, fleetmap_agent and fleetmap_view "
                      "sections, given to each process as --config (docs/configuration.md)");
  command->callback([args, exit_code] { *exit_code = RunSim(*args); });
}

}  // namespace fleetmap::bench
