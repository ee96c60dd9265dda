#include "cli/rasterize_command.hpp"

#include <iostream>
#include <memory>

#include "cli/inputs/exit_codes.hpp"
#include "common/vector_map/rasterizer.hpp"

namespace fleetmap::cli {

int RunRasterize(const RasterizeCommandOptions& options, std::ostream& out, std::ostream& err) {
  auto fail = [&err](const std::string& message) {
    err << "fleetmap rasterize: " << message << "\n";
    return kExitBadInput;
  };
  if (options.resolution_given && !options.like_yaml.empty()) {
    return fail(options.vmap + ": --resolution and --like both set the geometry; pass one");
  }
  if (options.resolution_given) {
    if (Status s = CheckPositiveFinite("--resolution", options.resolution); !s.ok()) {
      return fail(options.vmap + ": " + s.message());
    }
  }
  StatusOr<vector_map::TiledVectorMap> tiled = ReadVmapInput(options.vmap);
  if (!tiled.ok()) return fail(tiled.status().message());

  grid::OccupancyGrid geometry;
  if (!options.like_yaml.empty()) {
    StatusOr<grid::LoadedMap> like = LoadGridInput(options.like_yaml, options.max_cells);
    if (!like.ok()) return fail(like.status().message());
    if (Status s = CheckAxisAligned(options.like_yaml, like->grid); !s.ok()) {
      return fail(s.message());
    }
    geometry = std::move(like->grid);
  } else {
    const double resolution = options.resolution_given
                                  ? options.resolution
                                  : ShortestDouble(static_cast<float>(tiled->resolution));
    StatusOr<grid::OccupancyGrid> bounds =
        TileBoundsGrid(*tiled, options.vmap, resolution, options.max_cells);
    if (!bounds.ok()) return fail(bounds.status().message());
    geometry = std::move(bounds).value();
  }

  StatusOr<grid::OccupancyGrid> raster =
      vector_map::Rasterizer().Rasterize(tiled->Merged(), geometry);
  if (!raster.ok()) return fail(options.vmap + ": " + raster.status().message());
  if (Status s = grid::SaveMap(*raster, options.output_yaml); !s.ok()) return fail(s.message());
  out << options.vmap << " -> " << options.output_yaml << " (" << raster->width() << " x "
      << raster->height() << " cells at " << raster->resolution() << " m)\n";
  out.flush();
  return out ? kExitOk : kExitBadInput;
}

void AddRasterizeCommand(CLI::App& app, int* exit_code) {
  auto options = std::make_shared<RasterizeCommandOptions>();
  CLI::App* cmd =
      app.add_subcommand("rasterize", "Turn a .vmap back into a three-state map_server map");
  cmd->add_option("vmap", options->vmap, ".vmap file")->required();
  cmd->add_option("-o,--output", options->output_yaml, "map YAML to write (image beside it)")
      ->required();
  cmd->add_option("--like", options->like_yaml, "Copy this map's size, resolution and origin");
  CLI::Option* resolution = cmd->add_option("--resolution", options->resolution,
                                            "Metres per cell (default: the .vmap's resolution)");
  cmd->add_option("--max-cells", options->max_cells, "Refuse grids with more cells than this")
      ->check(CLI::PositiveNumber);
  cmd->callback([options, resolution, exit_code]() {
    options->resolution_given = resolution->count() > 0;
    *exit_code = RunRasterize(*options, std::cout, std::cerr);
  });
}

}  // namespace fleetmap::cli
