// fleetmap: the offline map tool. Each of the tool's subcommands lives in its own
// cli/<name>_command.{hpp,cpp}; the lab's (`sim`, `bench ...`) come from the bench/ libraries,
// one per experiment, under the same names as ever.

#include <CLI/CLI.hpp>

#include "bench/extrapolation/bench_extrapolation_command.hpp"
#include "bench/fleet/bench_capacity_command.hpp"
#include "bench/fleet/bench_failover_command.hpp"
#include "bench/fleet/bench_fleet_command.hpp"
#include "bench/fleet/bench_flood_command.hpp"
#include "bench/fleet/bench_loss_command.hpp"
#include "bench/fleet/bench_quarantine_command.hpp"
#include "bench/fleet/sim_command.hpp"
#include "bench/objects/bench_objects_command.hpp"
#include "bench/paper/bench_paper_command.hpp"
#include "bench/register/bench_register_command.hpp"
#include "bench/route_graph/bench_route_graph_command.hpp"
#include "bench/vectorize/bench_vectorize_command.hpp"
#include "cli/admit_command.hpp"
#include "cli/compare_command.hpp"
#include "cli/extrapolate_command.hpp"
#include "cli/info_command.hpp"
#include "cli/inputs/exit_codes.hpp"
#include "cli/learn_objects_command.hpp"
#include "cli/rasterize_command.hpp"
#include "cli/register_command.hpp"
#include "cli/render_command.hpp"
#include "cli/route_graph_command.hpp"
#include "cli/save_map_command.hpp"
#include "cli/security_command.hpp"
#include "cli/terrain_command.hpp"
#include "cli/validate_command.hpp"
#include "cli/vectorize_command.hpp"
#include "cli/view_command.hpp"
#include "common/config/command_line.hpp"

int main(int argc, char** argv) {
  CLI::App app{"fleetmap: the offline map tool of the fleetmap map server"};
  app.require_subcommand(1);
  int exit_code = fleetmap::cli::kExitOk;
  // Registration order is the order `fleetmap --help` lists the commands in.
  fleetmap::cli::AddInfoCommand(app, &exit_code);
  fleetmap::bench::AddSimCommand(app, &exit_code);
  fleetmap::bench::AddBenchFleetCommand(app, &exit_code);
  fleetmap::bench::AddBenchLossCommand(app, &exit_code);
  fleetmap::bench::AddBenchQuarantineCommand(app, &exit_code);
  fleetmap::bench::AddBenchFailoverCommand(app, &exit_code);
  fleetmap::bench::AddBenchCapacityCommand(app, &exit_code);
  fleetmap::bench::AddBenchFloodCommand(app, &exit_code);
  fleetmap::cli::AddTerrainCommand(app, &exit_code);
  fleetmap::bench::AddBenchPaperCommand(app, &exit_code);
  fleetmap::cli::AddVectorizeCommand(app, &exit_code);
  fleetmap::cli::AddValidateCommand(app, &exit_code);
  fleetmap::cli::AddRasterizeCommand(app, &exit_code);
  fleetmap::cli::AddCompareCommand(app, &exit_code);
  fleetmap::cli::AddRenderCommand(app, &exit_code);
  fleetmap::bench::AddBenchVectorizeCommand(app, &exit_code);
  fleetmap::cli::AddExtrapolateCommand(app, &exit_code);
  fleetmap::bench::AddBenchExtrapolationCommand(app, &exit_code);
  fleetmap::cli::AddLearnObjectsCommand(app, &exit_code);
  fleetmap::bench::AddBenchObjectsCommand(app, &exit_code);
  fleetmap::cli::AddRegisterCommand(app, &exit_code);
  fleetmap::bench::AddBenchRegisterCommand(app, &exit_code);
  fleetmap::cli::AddSecurityCommand(app, &exit_code);
  fleetmap::cli::AddSaveMapCommand(app, &exit_code);
  const auto view_config = fleetmap::cli::AddViewCommand(app, &exit_code);
  fleetmap::cli::AddAdmitCommand(app, &exit_code);
  fleetmap::cli::AddRouteGraphCommand(app, &exit_code);
  fleetmap::bench::AddBenchRouteGraphCommand(app, &exit_code);
  if (const auto exit_now =
          fleetmap::config::ParseCommandLine(app, argc, argv, {view_config.get()})) {
    return *exit_now;
  }
  return exit_code;
}
