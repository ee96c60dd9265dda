// fleetmap: the offline map tool. Each subcommand lives in its own <name>_command.{hpp,cpp}.

#include <CLI/CLI.hpp>

#include "bench/extrapolation/bench_extrapolation_command.hpp"
#include "bench/fleet/bench_fleet_command.hpp"
#include "bench/fleet/bench_loss_command.hpp"
#include "bench/objects/bench_objects_command.hpp"
#include "bench/paper/bench_paper_command.hpp"
#include "bench/vectorize/bench_vectorize_command.hpp"
#include "cli/compare_command.hpp"
#include "cli/exit_codes.hpp"
#include "cli/extrapolate_command.hpp"
#include "cli/info_command.hpp"
#include "cli/learn_objects_command.hpp"
#include "cli/rasterize_command.hpp"
#include "cli/render_command.hpp"
#include "bench/fleet/sim_command.hpp"
#include "cli/terrain_command.hpp"
#include "cli/validate_command.hpp"
#include "cli/vectorize_command.hpp"

int main(int argc, char** argv) {
  CLI::App app{"fleetmap: the offline map tool of the fleetmap map server"};
  app.require_subcommand(1);
  int exit_code = fleetmap::cli::kExitOk;
  fleetmap::cli::AddInfoCommand(app, &exit_code);
  fleetmap::cli::AddSimCommand(app, &exit_code);
  fleetmap::cli::AddBenchFleetCommand(app, &exit_code);
  fleetmap::cli::AddBenchLossCommand(app, &exit_code);
  fleetmap::cli::AddTerrainCommand(app, &exit_code);
  fleetmap::cli::AddBenchPaperCommand(app, &exit_code);
  fleetmap::cli::AddVectorizeCommand(app, &exit_code);
  fleetmap::cli::AddValidateCommand(app, &exit_code);
  fleetmap::cli::AddRasterizeCommand(app, &exit_code);
  fleetmap::cli::AddCompareCommand(app, &exit_code);
  fleetmap::cli::AddRenderCommand(app, &exit_code);
  fleetmap::cli::AddBenchVectorizeCommand(app, &exit_code);
  fleetmap::cli::AddExtrapolateCommand(app, &exit_code);
  fleetmap::cli::AddBenchExtrapolationCommand(app, &exit_code);
  fleetmap::cli::AddLearnObjectsCommand(app, &exit_code);
  fleetmap::cli::AddBenchObjectsCommand(app, &exit_code);
  CLI11_PARSE(app, argc, argv);
  return exit_code;
}
