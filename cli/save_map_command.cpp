#include "cli/save_map_command.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <iostream>
#include <memory>

#include "cli/georef_option.hpp"
#include "cli/inputs/exit_codes.hpp"
#include "common/core/file_io.hpp"
#include "common/core/progress_line.hpp"
#include "common/core/wake_up.hpp"
#include "common/gis/georeference_file.hpp"
#include "common/gis/georeferenced_geojson.hpp"
#include "common/grid/map_io.hpp"
#include "common/transport/occupancy_grid_reader.hpp"
#include "common/transport/participant.hpp"
#include "common/transport/topics.hpp"
#include "common/transport/vector_tile_reader.hpp"
#include "common/transport/vmap_file.hpp"
#include "common/vector_map/geojson.hpp"

namespace fleetmap::cli {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

constexpr int kExitNoMap = 1;

constexpr char kDescription[] = R"(
Waits for the fused map a fleetmap-server publishes on rt/fleetmap/map (reliable, transient local:
the newest map arrives at once), keeps the newest for --settle seconds, then writes map_server
YAML + image as nav2's map_saver does (trinary: 0 occupied, 254 free, 205 unknown). Exit 1 when no
map comes within --timeout; the message names the domain.)";

// Refuses a path whose folder is missing or not writable before waiting for anything.
Status CheckWritable(const std::string& path, const char* what) {
  if (path.empty()) return Status::Ok();
  const fs::path folder = fs::path(path).has_parent_path() ? fs::path(path).parent_path() : ".";
  std::error_code error;
  if (!fs::is_directory(folder, error)) {
    return InvalidArgumentError(
        fmt::format("{} {}: the folder {} does not exist", what, path, folder.string()));
  }
  if (::access(folder.c_str(), W_OK) != 0) {
    return InvalidArgumentError(
        fmt::format("{} {}: the folder {} is not writable", what, path, folder.string()));
  }
  if (fs::is_directory(path, error)) {
    return InvalidArgumentError(fmt::format("{} {}: is a folder", what, path));
  }
  return Status::Ok();
}

// The fused tiles received, as one tiled map (fleet frame).
vector_map::TiledVectorMap Assemble(const std::map<TileId, transport::VectorTileMessage>& tiles) {
  vector_map::TiledVectorMap map;
  for (const auto& [key, tile] : tiles) {
    if (map.tiles.empty()) {
      map.tile_size = tile.tile_size;
      map.resolution = tile.map.resolution;
      map.epsilon = tile.map.epsilon;
      map.lattice = tile.map.lattice;
    }
    map.tiles.emplace(key, tile.map);
  }
  return map;
}

Status WriteVectorOutputs(const SaveMapOptions& options,
                          const std::map<TileId, transport::VectorTileMessage>& tiles,
                          const gis::Georeference* georeference, std::ostream& out) {
  if (options.vmap_path.empty() && options.geojson_path.empty()) return Status::Ok();
  if (tiles.empty()) {
    return UnavailableError("no fused tiles arrived on " +
                            std::string(transport::kFusedTilesTopic));
  }
  const vector_map::TiledVectorMap map = Assemble(tiles);
  if (!options.vmap_path.empty()) {
    FLEETMAP_RETURN_IF_ERROR(transport::WriteVmapFile(map, options.vmap_path));
    out << options.vmap_path << ": " << map.tiles.size() << " fused tiles\n";
  }
  if (!options.geojson_path.empty()) {
    FLEETMAP_ASSIGN_OR_RETURN(nlohmann::json geojson, vector_map::ToGeoJson(map.Merged()));
    if (georeference != nullptr) {
      StatusOr<nlohmann::json> placed = gis::GeoreferencedGeoJson(geojson, *georeference);
      if (!placed.ok()) return placed.status().WithContext(options.geojson_path);
      geojson = std::move(placed).value();
    }
    FLEETMAP_RETURN_IF_ERROR(WriteFileAtomically(options.geojson_path, geojson.dump() + "\n"));
    out << options.geojson_path << ": the fused vector map, " << map.tiles.size() << " tiles"
        << (georeference != nullptr ? ", WGS84 longitude / latitude" : "") << "\n";
  }
  return Status::Ok();
}

// NAME.georef.yaml beside the map YAML: where the fleet frame, the frame of the map's origin, is.
Status WriteGeoreferenceFile(const std::string& yaml_path, const gis::Georeference& georeference,
                             std::ostream& out) {
  const std::string path = gis::GeoreferenceFilePath(yaml_path);
  FLEETMAP_RETURN_IF_ERROR(WriteFileAtomically(
      path,
      gis::GeoreferenceFileText(georeference, fs::path(yaml_path).filename().string(), "fleet")));
  out << path << ": the fleet frame's georeference\n";
  return Status::Ok();
}

}  // namespace

int RunSaveMap(const SaveMapOptions& options, std::ostream& out, std::ostream& err) {
  const auto fail = [&](const Status& status, int code) {
    err << "fleetmap save-map: " << status.message() << "\n";
    return code;
  };
  if (options.image_format != "pgm" && options.image_format != "png") {
    return fail(InvalidArgumentError("--format must be pgm or png"), kExitBadInput);
  }
  for (const auto& [path, what] : {std::pair{options.yaml_path, "-o"},
                                   {options.vmap_path, "--vmap"},
                                   {options.geojson_path, "--geojson"}}) {
    if (const Status writable = CheckWritable(path, what); !writable.ok()) {
      return fail(writable, kExitBadInput);
    }
  }
  // Made before the wait, so that a georeference PROJ refuses is said at once.
  std::optional<gis::Georeference> georeference;
  if (options.georef) {
    StatusOr<gis::Georeference> made = gis::Georeference::Create(*options.georef);
    if (!made.ok()) return fail(made.status().WithContext("--georef"), kExitBadInput);
    georeference = std::move(made).value();
  }
  auto dds = options.fleet.Participant("fleetmap-save-map");
  if (!dds.ok()) return fail(dds.status(), kExitBadInput);
  auto participant = transport::Participant::Create(*dds);
  if (!participant.ok()) return fail(participant.status(), kExitBadInput);
  auto wake_up = std::make_shared<WakeUp>();
  // Readers go before the participant, on every path.
  std::unique_ptr<transport::OccupancyGridReader> maps;
  std::unique_ptr<transport::VectorTileReader> tiles;
  auto map_reader =
      transport::OccupancyGridReader::Create(**participant, transport::kFleetMapTopic, wake_up);
  if (!map_reader.ok()) return fail(map_reader.status(), 1);
  maps = std::move(map_reader).value();
  if (!options.vmap_path.empty() || !options.geojson_path.empty()) {
    auto tile_reader =
        transport::VectorTileReader::Create(**participant, transport::kFusedTilesTopic, wake_up);
    if (!tile_reader.ok()) return fail(tile_reader.status(), 1);
    tiles = std::move(tile_reader).value();
  }

  std::optional<transport::MapMessage> newest;
  std::map<TileId, transport::VectorTileMessage> fused_tiles;
  size_t rejected = 0;
  const auto start = Clock::now();
  std::optional<Clock::time_point> settled_at;
  auto next_note = start;
  const auto seconds = [](double s) {
    return std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(s));
  };
  const auto waited = [&start] {
    return std::chrono::duration<double>(Clock::now() - start).count();
  };
  const auto waiting = [&] {
    return fmt::format("waiting for the fused map on {} (DDS domain {}): {:.0f} / {:.0f} s",
                       transport::kFleetMapTopic, (*participant)->domain_id(), waited(),
                       options.timeout_s);
  };
  ProgressLine progress(err, {.terminal = options.err_is_terminal});
  while (true) {
    const auto now = Clock::now();
    if (settled_at && now >= *settled_at) break;
    if (!newest && now - start >= seconds(options.timeout_s)) break;
    if (!newest && now >= next_note) {
      progress.Update(waiting());
      next_note += std::chrono::seconds(1);
    }
    wake_up->WaitFor(std::chrono::milliseconds(100));
    for (StatusOr<transport::MapMessage>& map : maps->Drain()) {
      if (!map.ok()) {
        ++rejected;
        continue;
      }
      newest = std::move(map).value();
      if (!settled_at) {
        settled_at = Clock::now() + seconds(options.settle_s);
        progress.Finish(fmt::format("the fused map on {} (DDS domain {}) came after {:.1f} s",
                                    transport::kFleetMapTopic, (*participant)->domain_id(),
                                    waited()));
      }
    }
    if (tiles != nullptr) {
      for (transport::TileEvent& event : tiles->Drain()) {
        if (event.kind == transport::TileEvent::Kind::kTile) {
          fused_tiles.insert_or_assign(event.tile.tile, std::move(event.tile));
        } else if (event.kind == transport::TileEvent::Kind::kRemoved) {
          fused_tiles.erase(event.tile.tile);
        }
      }
    }
  }
  if (!newest) progress.Finish(waiting());
  const int domain = (*participant)->domain_id();
  tiles.reset();
  maps.reset();
  participant->reset();

  if (!newest) {
    return fail(UnavailableError(fmt::format(
                    "no fused map on {} within {:.0f} s on DDS domain {}{}: is a fleetmap-server "
                    "running there (--domain, $FLEETMAP_DOMAIN), and is the fleet secured (then "
                    "--security)?",
                    transport::kFleetMapTopic, options.timeout_s, domain,
                    rejected > 0 ? fmt::format(" ({} malformed samples refused)", rejected) : "")),
                kExitNoMap);
  }
  grid::MapSaveOptions save;
  save.image_format = options.image_format;
  save.occupied_thresh = options.occupied_thresh;
  save.free_thresh = options.free_thresh;
  if (const Status saved = grid::SaveMap(newest->grid, options.yaml_path, save); !saved.ok()) {
    return fail(saved, kExitBadInput);
  }
  out << options.yaml_path << ": the fused map, " << newest->grid.width() << " x "
      << newest->grid.height() << " cells at " << newest->grid.resolution() << " m\n";
  if (georeference) {
    if (const Status written = WriteGeoreferenceFile(options.yaml_path, *georeference, out);
        !written.ok()) {
      return fail(written, kExitBadInput);
    }
  } else if (std::error_code error;
             fs::exists(gis::GeoreferenceFilePath(options.yaml_path), error)) {
    // Not ours to delete: the fleet frame a user surveyed is usually the same from save to save.
    err << "fleetmap save-map: note: " << gis::GeoreferenceFilePath(options.yaml_path)
        << " from an earlier save is left as it is (no --georef given)\n";
  }
  const gis::Georeference* placed = georeference ? &*georeference : nullptr;
  if (const Status written = WriteVectorOutputs(options, fused_tiles, placed, out); !written.ok()) {
    return fail(written, kExitBadInput);
  }
  return kExitOk;
}

void AddSaveMapCommand(CLI::App& app, int* exit_code) {
  auto options = std::make_shared<SaveMapOptions>();
  CLI::App* command = app.add_subcommand(
      "save-map", "Save the fleet's fused map as map_server YAML + image (nav2's map saver)");
  command->footer(kDescription);
  command->add_option("-o,--output", options->yaml_path, "map_server YAML to write")->required();
  command->add_option("--format", options->image_format, "image format: pgm or png")
      ->capture_default_str();
  command->add_option("--occ", options->occupied_thresh, "occupied threshold written to the YAML")
      ->capture_default_str();
  command->add_option("--free", options->free_thresh, "free threshold written to the YAML")
      ->capture_default_str();
  command->add_option("--geojson", options->geojson_path, "also the fused vector map as GeoJSON");
  CLI::Option* georef = AddGeorefOption(command, "fleet", &options->georef);
  georef->description(
      georef->get_description() +
      "; also write NAME.georef.yaml beside the map YAML (the map YAML is unchanged)");
  command->add_option("--vmap", options->vmap_path, "also the fused vector tiles as .vmap");
  command->add_option("--timeout", options->timeout_s, "seconds to wait for the fused map")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  command->add_option("--settle", options->settle_s, "then keep the newest for this long")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  auto fleet = std::make_shared<FleetReaderFlags>(command, &options->fleet);
  command->callback([options, fleet, exit_code] {
    fleet->ApplyDomain();
    options->err_is_terminal = ProgressLine::StderrIsTerminal();
    *exit_code = RunSaveMap(*options, std::cout, std::cerr);
  });
}

}  // namespace fleetmap::cli
