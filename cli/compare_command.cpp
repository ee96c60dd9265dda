#include "cli/compare_command.hpp"

#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <utility>
#include <vector>

#include "cli/inputs/exit_codes.hpp"
#include "common/grid/occupancy_grid.hpp"
#include "common/metrics/map_quality.hpp"

namespace fleetmap::cli {
namespace {

std::string Geometry(const grid::OccupancyGrid& grid) {
  char buffer[160];
  std::snprintf(buffer, sizeof(buffer), "%d x %d cells at %.10g m, origin (%.10g, %.10g, %.10g)",
                grid.width(), grid.height(), grid.resolution(), grid.origin().x, grid.origin().y,
                grid.origin().yaw);
  return buffer;
}

// The metrics need one cell lattice: same size, resolution and origin.
Status CheckSameGeometry(const CompareCommandOptions& options, const grid::OccupancyGrid& robot,
                         const grid::OccupancyGrid& truth) {
  if (robot.width() != truth.width() || robot.height() != truth.height() ||
      !grid::SameResolution(robot.resolution(), truth.resolution()) ||
      !(robot.origin() == truth.origin())) {
    return InvalidArgumentError("sizes do not match: " + options.robot_yaml + " is " +
                                Geometry(robot) + ", " + options.truth_yaml + " is " +
                                Geometry(truth));
  }
  return Status::Ok();
}

std::string Score(const std::optional<double>& score) {
  if (!score) return "undefined";
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.2f %%", *score);
  return buffer;
}

}  // namespace

int RunCompare(const CompareCommandOptions& options, std::ostream& out, std::ostream& err) {
  auto fail = [&err](const std::string& message) {
    err << "fleetmap compare: " << message << "\n";
    return kExitBadInput;
  };
  if (options.window < 1) {
    return fail(options.robot_yaml + ": --window must be >= 1 cell, got " +
                std::to_string(options.window));
  }
  StatusOr<grid::LoadedMap> robot = LoadGridInput(options.robot_yaml, options.max_cells);
  if (!robot.ok()) return fail(robot.status().message());
  StatusOr<grid::LoadedMap> truth = LoadGridInput(options.truth_yaml, options.max_cells);
  if (!truth.ok()) return fail(truth.status().message());
  if (Status s = CheckSameGeometry(options, robot->grid, truth->grid); !s.ok()) {
    return fail(s.message());
  }
  metrics::QualityOptions quality;
  quality.window_width = options.window;
  quality.window_height = options.window;
  StatusOr<metrics::QualityScores> scores = metrics::CompareMaps(robot->grid, truth->grid, quality);
  if (!scores.ok()) return fail(options.robot_yaml + ": " + scores.status().message());

  const std::vector<std::pair<const char*, std::optional<double>>> rows = {
      {"MS", scores->map_score},
      {"CC", scores->cross_correlation},
      {"PC", scores->pearson_occupied},
      {"OPDF", scores->occupied_picture_distance},
      {"UPDF", scores->unoccupied_picture_distance}};
  if (options.json) {
    nlohmann::ordered_json json;
    json["robot"] = options.robot_yaml;
    json["truth"] = options.truth_yaml;
    json["window"] = options.window;
    for (const auto& [name, score] : rows) {
      json[name] = score ? nlohmann::ordered_json(*score) : nlohmann::ordered_json(nullptr);
    }
    out << json.dump(-1, ' ', false, nlohmann::ordered_json::error_handler_t::replace) << "\n";
  } else {
    out << options.robot_yaml << " against " << options.truth_yaml << " (window " << options.window
        << " cells)\n";
    for (const auto& [name, score] : rows) {
      char label[8];
      std::snprintf(label, sizeof(label), "%-5s", name);
      out << label << Score(score) << "\n";
    }
  }
  out.flush();
  return out ? kExitOk : kExitBadInput;
}

void AddCompareCommand(CLI::App& app, int* exit_code) {
  auto options = std::make_shared<CompareCommandOptions>();
  CLI::App* cmd = app.add_subcommand(
      "compare",
      "Map-quality metrics (MS, CC, PC, OPDF, UPDF) of a robot map against ground truth");
  cmd->add_option("robot", options->robot_yaml, "robot map (map_server YAML)")->required();
  cmd->add_option("truth", options->truth_yaml, "ground truth (map_server YAML)")->required();
  cmd->add_flag("--json", options->json, "Print one JSON line instead of text");
  cmd->add_option("--window", options->window, "OPDF / UPDF search window in cells")
      ->capture_default_str();
  cmd->add_option("--max-cells", options->max_cells, "Refuse grids with more cells than this")
      ->check(CLI::PositiveNumber);
  cmd->callback(
      [options, exit_code]() { *exit_code = RunCompare(*options, std::cout, std::cerr); });
}

}  // namespace fleetmap::cli
