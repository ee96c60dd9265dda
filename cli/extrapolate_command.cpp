#include "cli/extrapolate_command.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>

#include "cli/extrapolation_outputs.hpp"
#include "cli/georef_option.hpp"
#include "cli/inputs/exit_codes.hpp"
#include "common/core/file_io.hpp"
#include "common/extrapolation/door_detector.hpp"
#include "common/extrapolation/entities_json.hpp"
#include "common/extrapolation/extrapolator.hpp"
#include "common/extrapolation/ply_reader.hpp"
#include "common/extrapolation/predicted_free_grid.hpp"
#include "common/extrapolation/stairs_detector.hpp"
#include "common/extrapolation/submap_graph_json.hpp"
#include "common/grid/map_io.hpp"

namespace fleetmap::cli {
namespace {

namespace ex = extrapolation;

std::string ThresholdName(double p_th) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "pth_%.2f", p_th);
  return buffer;
}

// Writes everything for one threshold into `dir`; returns the summary line.
StatusOr<std::string> WriteThreshold(const grid::OccupancyGrid& map,
                                     const scene::Entities& entities, double p_th,
                                     bool building_outline,
                                     const std::optional<gis::GeoOrigin>& georef,
                                     const std::string& dir, std::ostream& err) {
  ex::ExtrapolationOptions options;
  options.p_th = p_th;
  options.door_building_outline = building_outline;
  options.door_split_between_doors = building_outline;
  FLEETMAP_ASSIGN_OR_RETURN(const ex::ExtrapolationResult result,
                            ex::Extrapolate(map, entities, options));
  for (const std::string& warning : result.warnings) {
    err << "fleetmap extrapolate: warning: p_th " << p_th << ": " << warning << "\n";
  }
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) return InvalidArgumentError(dir + ": cannot create the directory: " + ec.message());

  std::vector<std::string> grid_files(result.graph.submaps.size());
  size_t observed_submaps = 0;
  for (size_t i = 0; i < result.graph.submaps.size(); ++i) {
    const scene::Submap& s = result.graph.submaps[i];
    if (s.kind == scene::SubmapKind::kObserved) {
      ++observed_submaps;  // a part of the local map: not written again
      continue;
    }
    grid_files[i] = "submap_" + std::to_string(s.id) + ".yaml";
    FLEETMAP_RETURN_IF_ERROR(grid::SaveMap(ex::SubmapGridInMapFrame(s), dir + "/" + grid_files[i]));
  }
  const ex::FloorGrids floor = ex::ComposeFloorGrids(map, result);
  FLEETMAP_RETURN_IF_ERROR(grid::SaveMap(floor.predicted_free, dir + "/predicted_free.yaml"));
  FLEETMAP_RETURN_IF_ERROR(grid::SaveMap(floor.extrapolated, dir + "/extrapolated.yaml"));
  nlohmann::json graph = ex::SubmapGraphToJson(result.graph, grid_files);
  graph["p_th"] = p_th;
  graph["warnings"] = result.warnings;
  const double cell_area = map.resolution() * map.resolution();
  graph["floor"] = {{"observed_free_m2", floor.observed_free_cells * cell_area},
                    {"predicted_free_m2", floor.predicted_free_cells * cell_area},
                    {"files", {"predicted_free.yaml", "extrapolated.yaml"}}};
  FLEETMAP_RETURN_IF_ERROR(WriteFileAtomically(dir + "/graph.json", graph.dump(2) + "\n"));
  FLEETMAP_ASSIGN_OR_RETURN(nlohmann::json plane, PredictedFreeGeoJson(result, p_th));
  const std::string geojson_path = dir + "/predicted_free.geojson";
  StatusOr<nlohmann::json> predicted_free = GeoJsonToWrite(std::move(plane), georef);
  if (!predicted_free.ok()) return predicted_free.status().WithContext(geojson_path);
  FLEETMAP_RETURN_IF_ERROR(WriteFileAtomically(geojson_path, predicted_free->dump() + "\n"));
  FLEETMAP_RETURN_IF_ERROR(WriteOverlayPng(result, floor, entities, dir + "/overlay.png"));

  std::ostringstream line;
  const double observed = floor.observed_free_cells * cell_area;
  const double predicted = floor.predicted_free_cells * cell_area;
  char buffer[200];
  std::snprintf(
      buffer, sizeof(buffer),
      "p_th %.2f: %zu sub-maps (%zu observed, one per place; %zu predicted), observed free "
      "%.1f m2, predicted free on this floor %.1f m2 (%+.1f %%)",
      p_th, result.graph.submaps.size(), observed_submaps,
      result.graph.submaps.size() - observed_submaps, observed, predicted,
      observed > 0 ? 100.0 * predicted / observed : 0.0);
  line << buffer << " -> " << dir;
  return line.str();
}

}  // namespace

int RunExtrapolate(const ExtrapolateCommandOptions& options, std::ostream& out, std::ostream& err) {
  const std::string prefix = "fleetmap extrapolate: ";
  auto fail = [&](const std::string& message) {
    err << prefix << message << "\n";
    return kExitBadInput;
  };
  if (options.p_th.empty()) return fail("--pth: give at least one threshold");
  for (double p : options.p_th) {
    if (!(p > 0.0 && p < 1.0)) {
      return fail("--pth: " + std::to_string(p) + " is not in (0, 1)");
    }
  }
  std::optional<Point2> viewpoint;
  if (!options.viewpoint.empty()) {
    if (options.viewpoint.size() != 2 || !std::isfinite(options.viewpoint[0]) ||
        !std::isfinite(options.viewpoint[1])) {
      return fail("--viewpoint: give two finite numbers X,Y");
    }
    viewpoint = Point2(options.viewpoint[0], options.viewpoint[1]);
  }
  StatusOr<grid::LoadedMap> loaded = LoadGridInput(options.map_yaml, options.max_cells);
  if (!loaded.ok()) return fail(loaded.status().message());
  const grid::OccupancyGrid& map = loaded->grid;

  std::ifstream file(options.entities_json, std::ios::binary);
  if (!file) return fail(options.entities_json + ": cannot open the entities file");
  std::ostringstream text;
  text << file.rdbuf();
  StatusOr<ex::ParsedEntities> parsed = ex::ParseEntitiesJson(text.str(), options.entities_json);
  if (!parsed.ok()) return fail(parsed.status().message());
  for (const std::string& warning : parsed->warnings) {
    err << prefix << "warning: " << warning << "\n";
  }
  scene::Entities entities = parsed->entities;

  if (!options.cloud_ply.empty()) {
    StatusOr<ex::PointCloud> cloud = ex::ReadPly(options.cloud_ply, options.max_points);
    if (!cloud.ok()) return fail(cloud.status().message());
    if (cloud->empty()) {
      err << prefix << "warning: " << options.cloud_ply
          << ": the point cloud is empty: no stairs or doors detected\n";
    }
    for (ex::DetectedStairs& stairs : ex::DetectStairs(*cloud)) {
      stairs.entity.id = "cloud_" + stairs.entity.id;
      entities.stairs.push_back(stairs.entity);
    }
    for (ex::DetectedDoor& door : ex::DetectDoors(*cloud, viewpoint)) {
      door.entity.id = "cloud_" + door.entity.id;
      entities.doors.push_back(door.entity);
    }
    out << options.cloud_ply << ": " << cloud->size() << " points\n";
  }
  std::error_code ec;
  std::filesystem::create_directories(options.out_dir, ec);
  if (ec) return fail("--out: " + options.out_dir + ": cannot create the directory");
  if (Status s =
          WriteFileAtomically(options.out_dir + "/entities.json", ex::EntitiesToJson(entities));
      !s.ok()) {
    return fail(s.message());
  }
  out << "entities: " << entities.doors.size() << " doors, " << entities.stairs.size()
      << " stairs, " << entities.people.size() << " people\n";
  for (double p_th : options.p_th) {
    StatusOr<std::string> line =
        WriteThreshold(map, entities, p_th, options.building_outline, options.georef,
                       options.out_dir + "/" + ThresholdName(p_th), err);
    if (!line.ok()) return fail(line.status().message());
    out << *line << "\n";
  }
  return kExitOk;
}

void AddExtrapolateCommand(CLI::App& app, int* exit_code) {
  auto options = std::make_shared<ExtrapolateCommandOptions>();
  CLI::App* command = app.add_subcommand(
      "extrapolate", "Predict unseen space behind doors, up stairs and along people's tracks");
  command->add_option("--map", options->map_yaml, "local map (map_server YAML)")->required();
  command->add_option("--entities", options->entities_json, "entities JSON")->required();
  command->add_option("--cloud", options->cloud_ply,
                      "point cloud (PLY) to detect stairs and doors");
  command->add_option("--viewpoint", options->viewpoint, "sensor position X,Y of the cloud")
      ->delimiter(',');
  command->add_option("--out", options->out_dir, "output directory")->required();
  command->add_option("--pth", options->p_th, "thresholds in (0, 1), comma separated")
      ->delimiter(',')
      ->capture_default_str();
  command->add_option("--max-cells", options->max_cells, "largest map accepted (cells)")
      ->capture_default_str();
  command->add_option("--max-points", options->max_points, "largest point cloud accepted")
      ->capture_default_str();
  AddGeorefOption(command, "map", &options->georef);
  command->add_flag("!--no-building-outline", options->building_outline,
                    "door predictions without the building's outline and the other doors in "
                    "their wall (before issue 36)");
  command->callback(
      [options, exit_code] { *exit_code = RunExtrapolate(*options, std::cout, std::cerr); });
}

}  // namespace fleetmap::cli
