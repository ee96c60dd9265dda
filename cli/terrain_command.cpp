#include "cli/terrain_command.hpp"

#include <iostream>
#include <memory>

#include "cli/georef_option.hpp"
#include "cli/inputs/exit_codes.hpp"
#include "common/core/file_io.hpp"
#include "common/grid/map_io.hpp"
#include "common/sim/terrain_generator.hpp"
#include "common/sim/terrain_geojson.hpp"
#include "common/sim/terrain_rasterizer.hpp"

namespace fleetmap::cli {

int RunTerrain(const TerrainCommandOptions& options, std::ostream& out, std::ostream& err) {
  const std::optional<sim::TerrainKind> kind = sim::TerrainKindFromName(options.kind);
  if (!kind) {
    err << "fleetmap terrain: --kind '" << options.kind
        << "' is unknown: use maze, office, unstructured or warehouse\n";
    return kExitBadInput;
  }
  const StatusOr<sim::TerrainGenerator> generator =
      sim::TerrainGenerator::Create({.kind = *kind, .size = options.size, .seed = options.seed});
  if (!generator.ok()) {
    err << "fleetmap terrain: --size: " << generator.status().message() << "\n";
    return kExitBadInput;
  }
  const sim::Terrain terrain = generator->Generate();
  const StatusOr<grid::OccupancyGrid> truth = sim::RasterizeTerrain(terrain, options.resolution);
  if (!truth.ok()) {
    err << "fleetmap terrain: --resolution: " << truth.status().message() << "\n";
    return kExitBadInput;
  }
  if (const Status saved = grid::SaveMap(*truth, options.output_yaml); !saved.ok()) {
    err << "fleetmap terrain: " << saved.message() << "\n";
    return kExitBadInput;
  }
  if (!options.geojson.empty()) {
    StatusOr<nlohmann::json> plane = sim::TerrainToGeoJson(terrain);
    StatusOr<nlohmann::json> geojson =
        plane.ok() ? GeoJsonToWrite(std::move(plane).value(), options.georef) : plane.status();
    const Status written = geojson.ok()
                               ? WriteFileAtomically(options.geojson, geojson->dump(1) + "\n")
                               : geojson.status().WithContext(options.geojson);
    if (!written.ok()) {
      err << "fleetmap terrain: " << written.message() << "\n";
      return kExitBadInput;
    }
  }
  out << "terrain " << sim::TerrainKindName(terrain.kind) << " " << terrain.size << " m, seed "
      << terrain.seed << ": " << truth->width() << " x " << truth->height() << " cells, "
      << terrain.walls.size() << " walls, " << terrain.polygons.size() << " polygons, "
      << terrain.doors.size() << " doors -> " << options.output_yaml << "\n";
  return kExitOk;
}

void AddTerrainCommand(CLI::App& app, int* exit_code) {
  auto options = std::make_shared<TerrainCommandOptions>();
  CLI::App* command =
      app.add_subcommand("terrain", "Generate a simulated terrain and its ground-truth grid");
  command->add_option("--kind", options->kind, "maze, office, unstructured or warehouse")
      ->capture_default_str();
  command->add_option("--size", options->size, "side of the square terrain (m), 5..400")
      ->capture_default_str();
  command->add_option("--seed", options->seed, "random seed")->capture_default_str();
  command->add_option("--resolution", options->resolution, "ground-truth cell size (m)")
      ->capture_default_str();
  command->add_option("-o,--output", options->output_yaml, "map YAML to write (PGM beside it)")
      ->required();
  CLI::Option* geojson = command->add_option("--geojson", options->geojson,
                                             "also write the exact geometry as GeoJSON");
  AddGeorefOption(command, "map", &options->georef)->needs(geojson);
  command->callback(
      [options, exit_code] { *exit_code = RunTerrain(*options, std::cout, std::cerr); });
}

}  // namespace fleetmap::cli
