#include "cli/vectorize_command.hpp"

#include <chrono>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <span>

#include "cli/georef_option.hpp"
#include "cli/inputs/exit_codes.hpp"
#include "common/core/file_io.hpp"
#include "common/metrics/grid_sizes.hpp"
#include "common/vector_map/geojson.hpp"
#include "common/vector_map/png.hpp"
#include "common/vector_map/svg.hpp"

namespace fleetmap::cli {
namespace {

std::optional<vector_map::VectorizeMethod> MethodFromName(const std::string& name) {
  if (name == "default") return vector_map::VectorizeMethod::kDefault;
  if (name == "paper") return vector_map::VectorizeMethod::kPaper;
  return std::nullopt;
}

// The optional pictures, drawn from the merged tiles (fleet frame = map frame).
Status WritePictures(const VectorizeCommandOptions& options, const vector_map::VectorMap& merged,
                     const grid::OccupancyGrid& grid) {
  if (!options.geojson_path.empty()) {
    FLEETMAP_ASSIGN_OR_RETURN(nlohmann::json plane, vector_map::ToGeoJson(merged));
    StatusOr<nlohmann::json> geojson = GeoJsonToWrite(std::move(plane), options.georef);
    if (!geojson.ok()) return geojson.status().WithContext(options.geojson_path);
    FLEETMAP_RETURN_IF_ERROR(WriteFileAtomically(options.geojson_path, geojson->dump() + "\n"));
  }
  if (!options.svg_path.empty()) {
    FLEETMAP_RETURN_IF_ERROR(WriteFileAtomically(options.svg_path, vector_map::ToSvg(merged)));
  }
  if (!options.png_path.empty()) {
    FLEETMAP_ASSIGN_OR_RETURN(const std::vector<uint8_t> png,
                              vector_map::RenderVectorMapPng(merged, grid));
    FLEETMAP_RETURN_IF_ERROR(WriteFileAtomically(options.png_path, png));
  }
  return Status::Ok();
}

}  // namespace

int RunVectorize(const VectorizeCommandOptions& options, std::ostream& out, std::ostream& err) {
  auto fail = [&err](const std::string& message) {
    err << "fleetmap vectorize: " << message << "\n";
    return kExitBadInput;
  };
  const std::optional<vector_map::VectorizeMethod> method = MethodFromName(options.method);
  if (!method) {
    return fail(options.map_yaml + ": unknown --method '" + options.method +
                "' (expected default or paper)");
  }
  if (options.epsilon_given) {
    if (Status s = CheckPositiveFinite("--epsilon", options.epsilon); !s.ok()) {
      return fail(options.map_yaml + ": " + s.message());
    }
  }
  if (options.free_epsilon_given) {
    if (Status s = CheckPositiveFinite("--free-epsilon", options.free_epsilon); !s.ok()) {
      return fail(options.map_yaml + ": " + s.message());
    }
  }
  if (Status s = CheckPositiveFinite("--tile-size", options.tile_size); !s.ok()) {
    return fail(options.map_yaml + ": " + s.message());
  }
  StatusOr<grid::LoadedMap> loaded = LoadGridInput(options.map_yaml, options.max_cells);
  if (!loaded.ok()) return fail(loaded.status().message());
  const grid::OccupancyGrid& grid = loaded->grid;
  if (Status s = CheckAxisAligned(options.map_yaml, grid); !s.ok()) return fail(s.message());

  vector_map::TiledVectorizeOptions tiled;
  tiled.tile_size = options.tile_size;
  tiled.vectorizer.method = *method;
  tiled.vectorizer.epsilon = options.epsilon_given ? options.epsilon : 0.0;
  tiled.vectorizer.free_epsilon = options.free_epsilon_given ? options.free_epsilon : 0.0;
  const auto start = std::chrono::steady_clock::now();
  StatusOr<vector_map::TiledVectorMap> map =
      vector_map::VectorizeTiled(grid, Transform2::Identity(), tiled);
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  if (!map.ok()) return fail(options.map_yaml + ": " + map.status().message());
  size_t dropped_rings = 0;
  StatusOr<std::string> bytes = EncodeVmapBytes(&*map, &dropped_rings);
  if (!bytes.ok()) return fail(options.map_yaml + ": cannot encode: " + bytes.status().message());
  if (Status s = WriteFileAtomically(options.output_vmap, *bytes); !s.ok())
    return fail(s.message());
  if (Status s = WritePictures(options, map->Merged(), grid); !s.ok()) return fail(s.message());
  StatusOr<metrics::CompressedSizes> sizes = metrics::MeasureBytes(
      std::span(reinterpret_cast<const uint8_t*>(bytes->data()), bytes->size()));
  if (!sizes.ok()) return fail(sizes.status().message());

  if (options.json) {
    nlohmann::ordered_json json;
    json["file"] = options.map_yaml;
    json["output"] = options.output_vmap;
    json["method"] = options.method;
    json["epsilon"] = map->epsilon;
    json["free_epsilon"] = options.free_epsilon_given ? options.free_epsilon : map->epsilon;
    json["tile_size"] = map->tile_size;
    json["vertices"] = map->ObstacleVertexCount();
    json["segments"] = map->ObstacleSegmentCount();
    json["free_vertices"] = map->FreeVertexCount();
    json["tiles"] = map->tiles.size();
    json["bytes"] = {{"raw", sizes->raw}, {"zstd", sizes->zstd}};
    json["ms"] = ms;
    json["dropped_free_rings"] = dropped_rings;  // 0 unless the codec refuses rings without area
    out << json.dump(-1, ' ', false, nlohmann::ordered_json::error_handler_t::replace) << "\n";
  } else {
    out << options.map_yaml << " -> " << options.output_vmap << " (" << options.method
        << ", epsilon " << map->epsilon << " m, " << map->tiles.size() << " tiles of "
        << map->tile_size << " m)\n"
        << "obstacles: " << map->ObstacleVertexCount() << " vertices, "
        << map->ObstacleSegmentCount() << " segments; free space: " << map->FreeVertexCount()
        << " vertices\n"
        << "size:      " << sizes->raw << " bytes (" << sizes->zstd << " with zstd -19)\n"
        << "time:      " << ms << " ms\n";
    if (dropped_rings > 0) {
      out << "note:      " << dropped_rings
          << " free rings of one or two vertices left out (the .vmap codec refuses them)\n";
    }
  }
  out.flush();
  return out ? kExitOk : kExitBadInput;
}

void AddVectorizeCommand(CLI::App& app, int* exit_code) {
  auto options = std::make_shared<VectorizeCommandOptions>();
  CLI::App* cmd = app.add_subcommand("vectorize", "Vectorize a map tile by tile into a .vmap file");
  cmd->add_option("map", options->map_yaml, "map_server YAML file")->required();
  cmd->add_option("-o,--output", options->output_vmap, ".vmap file to write")->required();
  CLI::Option* epsilon = cmd->add_option("--epsilon", options->epsilon,
                                         "Error bound in metres (default sqrt(2) * resolution)");
  CLI::Option* free_epsilon = cmd->add_option(
      "--free-epsilon", options->free_epsilon,
      "Tolerance of the free-space outlines in metres (default epsilon; smaller: more faithful "
      "free / unknown borders, more bytes)");
  cmd->add_option("--method", options->method, "default (both constraints hold) or paper");
  cmd->add_option("--tile-size", options->tile_size, "Tile side in metres")->capture_default_str();
  CLI::Option* geojson =
      cmd->add_option("--geojson", options->geojson_path, "Also write GeoJSON here");
  AddGeorefOption(cmd, "map", &options->georef)->needs(geojson);
  cmd->add_option("--svg", options->svg_path, "Also write an SVG picture here");
  cmd->add_option("--png", options->png_path, "Also write a PNG picture here");
  cmd->add_flag("--json", options->json, "Print one JSON line instead of text");
  cmd->add_option("--max-cells", options->max_cells, "Refuse grids with more cells than this")
      ->check(CLI::PositiveNumber);
  cmd->callback([options, epsilon, free_epsilon, exit_code]() {
    options->epsilon_given = epsilon->count() > 0;
    options->free_epsilon_given = free_epsilon->count() > 0;
    *exit_code = RunVectorize(*options, std::cout, std::cerr);
  });
}

}  // namespace fleetmap::cli
