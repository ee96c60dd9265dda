#include "cli/info_command.hpp"

#include <algorithm>
#include <array>
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "cli/inputs/exit_codes.hpp"
#include "common/core/number_format.hpp"
#include "common/core/types.hpp"
#include "common/grid/map_io.hpp"
#include "common/grid/occupancy_grid.hpp"

namespace fleetmap::cli {
namespace {

// The map-frame box around the grid's footprint (the four outer corners, rotated by the yaw).
struct Bounds {
  double min_x;
  double min_y;
  double max_x;
  double max_y;
};

Bounds FootprintBounds(const grid::OccupancyGrid& grid) {
  const Transform2 map_from_grid = grid.origin().ToTransform();
  const double width_m = grid.width() * grid.resolution();
  const double height_m = grid.height() * grid.resolution();
  const std::array<Point2, 4> corners = {Point2(0.0, 0.0), Point2(width_m, 0.0),
                                         Point2(0.0, height_m), Point2(width_m, height_m)};
  const Point2 first = map_from_grid * corners[0];
  Bounds bounds{first.x(), first.y(), first.x(), first.y()};
  for (const Point2& corner : corners) {
    const Point2 p = map_from_grid * corner;
    bounds.min_x = std::min(bounds.min_x, p.x());
    bounds.min_y = std::min(bounds.min_y, p.y());
    bounds.max_x = std::max(bounds.max_x, p.x());
    bounds.max_y = std::max(bounds.max_y, p.y());
  }
  return bounds;
}

// Metres to the millimetre: a bounds corner is 50 m, not 50.00000089 m.
std::string Metres(double value) { return FixedNumber(value, 3); }

std::string Percent(int64_t part, int64_t whole) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.1f%%", whole > 0 ? 100.0 * part / whole : 0.0);
  return buffer;
}

void PrintText(const std::string& yaml, const grid::LoadedMap& map, const Bounds& bounds,
               const grid::StateCounts& counts, std::ostream& out) {
  const grid::OccupancyGrid& g = map.grid;
  const grid::MapMetadata& meta = map.metadata;
  const int64_t cells = g.cell_count();
  out << "map:        " << yaml << "\n"
      << "image:      " << meta.image_path << "\n"
      << "size:       " << g.width() << " x " << g.height() << " cells (" << cells << ")\n"
      << "resolution: " << CleanNumber(g.resolution()) << " m/cell\n"
      << "origin:     x " << Metres(g.origin().x) << " m, y " << Metres(g.origin().y) << " m, yaw "
      << FixedNumber(g.origin().yaw, 4) << " rad\n"
      << "bounds:     x [" << Metres(bounds.min_x) << ", " << Metres(bounds.max_x) << "] m, y ["
      << Metres(bounds.min_y) << ", " << Metres(bounds.max_y) << "] m\n"
      << "occupied:   " << counts.occupied << " (" << Percent(counts.occupied, cells) << ")\n"
      << "free:       " << counts.free << " (" << Percent(counts.free, cells) << ")\n"
      << "unknown:    " << counts.unknown << " (" << Percent(counts.unknown, cells) << ")\n"
      << "mode:       " << grid::MapModeName(meta.mode) << "\n"
      << "negate:     " << (meta.negate ? 1 : 0) << "\n"
      << "thresholds: occupied " << CleanNumber(meta.occupied_thresh) << ", free "
      << CleanNumber(meta.free_thresh) << "\n";
}

void PrintJson(const std::string& yaml, const grid::LoadedMap& map, const Bounds& bounds,
               const grid::StateCounts& counts, std::ostream& out) {
  const grid::OccupancyGrid& g = map.grid;
  const grid::MapMetadata& meta = map.metadata;
  nlohmann::ordered_json json;
  json["file"] = yaml;
  json["image"] = meta.image_path;
  json["width"] = g.width();
  json["height"] = g.height();
  json["cells"] = g.cell_count();
  json["resolution"] = g.resolution();
  json["origin"] = {{"x", g.origin().x}, {"y", g.origin().y}, {"yaw", g.origin().yaw}};
  // Computed corners, to the micrometre: without float noise, exact enough for any use.
  const auto corner = [](double value) { return RoundToDecimals(value, 6); };
  json["bounds"] = {{"min_x", corner(bounds.min_x)},
                    {"min_y", corner(bounds.min_y)},
                    {"max_x", corner(bounds.max_x)},
                    {"max_y", corner(bounds.max_y)}};
  json["counts"] = {
      {"occupied", counts.occupied}, {"free", counts.free}, {"unknown", counts.unknown}};
  json["mode"] = std::string(grid::MapModeName(meta.mode));
  json["negate"] = meta.negate;
  json["occupied_thresh"] = meta.occupied_thresh;
  json["free_thresh"] = meta.free_thresh;
  // File names need not be UTF-8: replace bad bytes rather than throw.
  out << json.dump(-1, ' ', false, nlohmann::ordered_json::error_handler_t::replace) << "\n";
}

}  // namespace

int RunInfo(const InfoOptions& options, std::ostream& out, std::ostream& err) {
  grid::MapLoadOptions load_options;
  load_options.allow_outside_dir = options.allow_outside_dir;
  load_options.max_cells = options.max_cells;
  const StatusOr<grid::LoadedMap> map = grid::LoadMap(options.map_yaml, load_options);
  if (!map.ok()) {
    err << "fleetmap info: " << map.status().message() << "\n";
    return kExitBadInput;
  }
  // States are counted with the map's own thresholds (a value v is occupied when v / 100 is above
  // occupied_thresh), so a trinary map counts exactly its 100 / 0 / -1 cells.
  const grid::StateCounts counts = map->grid.CountStates(
      {.occupied = map->metadata.occupied_thresh, .free = map->metadata.free_thresh});
  const Bounds bounds = FootprintBounds(map->grid);
  if (options.json) {
    PrintJson(options.map_yaml, *map, bounds, counts, out);
  } else {
    PrintText(options.map_yaml, *map, bounds, counts, out);
  }
  out.flush();
  return out ? kExitOk : kExitBadInput;
}

void AddInfoCommand(CLI::App& app, int* exit_code) {
  auto options = std::make_shared<InfoOptions>();
  CLI::App* info = app.add_subcommand(
      "info", "Print a map's size, resolution, origin, bounds, cell counts and metadata");
  info->add_option("map", options->map_yaml, "map_server YAML file")->required();
  info->add_flag("--json", options->json, "Print one JSON object instead of text");
  info->add_flag("--allow-outside-dir", options->allow_outside_dir,
                 "Read an image outside the YAML's directory (refused by default)");
  info->add_option("--max-cells", options->max_cells, "Refuse images with more cells than this")
      ->check(CLI::PositiveNumber);
  info->callback([options, exit_code]() { *exit_code = RunInfo(*options, std::cout, std::cerr); });
}

}  // namespace fleetmap::cli
