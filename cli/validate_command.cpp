#include "cli/validate_command.hpp"

#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "cli/inputs/exit_codes.hpp"
#include "common/core/number_format.hpp"
#include "common/grid/occupancy_grid.hpp"
#include "common/vector_map/validator.hpp"

namespace fleetmap::cli {

int RunValidate(const ValidateCommandOptions& options, std::ostream& out, std::ostream& err) {
  auto fail = [&err](const std::string& message) {
    err << "fleetmap validate: " << message << "\n";
    return kExitBadInput;
  };
  StatusOr<grid::LoadedMap> loaded = LoadGridInput(options.map_yaml, options.max_cells);
  if (!loaded.ok()) return fail(loaded.status().message());
  const grid::OccupancyGrid& grid = loaded->grid;
  if (Status s = CheckAxisAligned(options.map_yaml, grid); !s.ok()) return fail(s.message());
  StatusOr<vector_map::TiledVectorMap> tiled = ReadVmapInput(options.vmap);
  if (!tiled.ok()) return fail(tiled.status().message());
  if (!grid::SameResolution(grid.resolution(), tiled->resolution)) {
    return fail(options.vmap + ": made from a grid of resolution " +
                CleanNumber(tiled->resolution) + " m, but " + options.map_yaml + " has " +
                CleanNumber(grid.resolution()) + " m");
  }
  if (!(tiled->epsilon > 0.0)) return fail(options.vmap + ": epsilon must be > 0");

  // Identity tiling: the fleet frame is the map frame, so the merged tiles are read in the grid's
  // frame. Validating the merged map (not tile by tile) checks points near a tile border against
  // the edges of both tiles, and every edge against the delimitation of the whole grid.
  vector_map::ValidatorOptions validator_options;
  validator_options.epsilon = StoredEpsilonBound(tiled->epsilon);
  StatusOr<vector_map::ValidationReport> report =
      vector_map::Validator(validator_options).Validate(tiled->Merged(), grid);
  if (!report.ok()) return fail(options.vmap + ": " + report.status().message());

  if (options.json) {
    nlohmann::ordered_json json;
    json["map"] = options.map_yaml;
    json["vmap"] = options.vmap;
    json["valid"] = report->ok();
    json["epsilon"] = validator_options.epsilon;
    json["delimitation_points"] = report->delimitation_points;
    json["uncovered_points"] = report->uncovered_points;
    json["worst_point_distance"] = report->worst_point_distance;
    json["segments"] = report->segments;
    json["discontinuous_segments"] = report->discontinuous_segments;
    json["worst_segment_distance"] = report->worst_segment_distance;
    out << json.dump(-1, ' ', false, nlohmann::ordered_json::error_handler_t::replace) << "\n";
  } else {
    out << options.vmap << " against " << options.map_yaml << " (epsilon "
        << validator_options.epsilon << " m): " << (report->ok() ? "valid" : "VIOLATED") << "\n"
        << "epsilon-error: " << report->uncovered_points << " of " << report->delimitation_points
        << " delimitation points uncovered, worst distance " << report->worst_point_distance
        << " m\n"
        << "continuity:    " << report->discontinuous_segments << " of " << report->segments
        << " segments discontinuous, worst distance " << report->worst_segment_distance
        << " m (sampled)\n";
  }
  out.flush();
  if (!out) return kExitBadInput;
  return report->ok() ? kExitOk : kExitConstraintViolated;
}

void AddValidateCommand(CLI::App& app, int* exit_code) {
  auto options = std::make_shared<ValidateCommandOptions>();
  CLI::App* cmd = app.add_subcommand(
      "validate", "Check a .vmap against its grid (exit 1 when a constraint is violated)");
  cmd->add_option("map", options->map_yaml, "map_server YAML file")->required();
  cmd->add_option("vmap", options->vmap, ".vmap file")->required();
  cmd->add_flag("--json", options->json, "Print one JSON line instead of text");
  cmd->add_option("--max-cells", options->max_cells, "Refuse grids with more cells than this")
      ->check(CLI::PositiveNumber);
  cmd->callback(
      [options, exit_code]() { *exit_code = RunValidate(*options, std::cout, std::cerr); });
}

}  // namespace fleetmap::cli
