#include "cli/render_command.hpp"

#include <iostream>
#include <memory>
#include <vector>

#include "cli/inputs/exit_codes.hpp"
#include "common/core/file_io.hpp"
#include "common/vector_map/png.hpp"
#include "common/vector_map/svg.hpp"

namespace fleetmap::cli {
namespace {

std::string Base64(const std::vector<uint8_t>& bytes) {
  static constexpr char kAlphabet[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string text;
  text.reserve((bytes.size() + 2) / 3 * 4);
  for (size_t i = 0; i < bytes.size(); i += 3) {
    const size_t n = std::min<size_t>(3, bytes.size() - i);
    uint32_t chunk = static_cast<uint32_t>(bytes[i]) << 16;
    if (n > 1) chunk |= static_cast<uint32_t>(bytes[i + 1]) << 8;
    if (n > 2) chunk |= bytes[i + 2];
    for (size_t k = 0; k < 4; ++k) {
      text += k <= n ? kAlphabet[(chunk >> (18 - 6 * k)) & 0x3f] : '=';
    }
  }
  return text;
}

// The grid's PNG inside an SVG, one cell = pixels_per_metre * resolution pixels.
std::string GridSvg(const grid::OccupancyGrid& grid, const std::vector<uint8_t>& png) {
  const double scale = vector_map::SvgOptions{}.pixels_per_metre * grid.resolution();
  const std::string width = std::to_string(grid.width() * scale);
  const std::string height = std::to_string(grid.height() * scale);
  return "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + width + "\" height=\"" + height +
         "\">\n<image width=\"" + width + "\" height=\"" + height +
         "\" style=\"image-rendering:pixelated\" href=\"data:image/png;base64," + Base64(png) +
         "\"/>\n</svg>\n";
}

Status RenderGrid(const RenderCommandOptions& options, bool svg) {
  FLEETMAP_ASSIGN_OR_RETURN(const grid::LoadedMap map,
                            LoadGridInput(options.input, options.max_cells));
  StatusOr<std::vector<uint8_t>> png = vector_map::EncodeGridPng(map.grid);
  if (!png.ok()) return png.status().WithContext(options.input);
  if (svg) return WriteFileAtomically(options.output, GridSvg(map.grid, *png));
  return WriteFileAtomically(options.output, *png);
}

Status RenderVmap(const RenderCommandOptions& options, bool svg) {
  FLEETMAP_ASSIGN_OR_RETURN(const vector_map::TiledVectorMap tiled, ReadVmapInput(options.input));
  const vector_map::VectorMap merged = tiled.Merged();
  if (svg) return WriteFileAtomically(options.output, vector_map::ToSvg(merged));
  grid::OccupancyGrid geometry;
  if (!options.like_yaml.empty()) {
    FLEETMAP_ASSIGN_OR_RETURN(grid::LoadedMap like,
                              LoadGridInput(options.like_yaml, options.max_cells));
    geometry = std::move(like.grid);
  } else {
    FLEETMAP_ASSIGN_OR_RETURN(
        geometry,
        TileBoundsGrid(tiled, options.input, ShortestDouble(static_cast<float>(tiled.resolution)),
                       options.max_cells));
  }
  StatusOr<std::vector<uint8_t>> png = vector_map::RenderVectorMapPng(merged, geometry);
  if (!png.ok()) return png.status().WithContext(options.input);
  return WriteFileAtomically(options.output, *png);
}

}  // namespace

int RunRender(const RenderCommandOptions& options, std::ostream& out, std::ostream& err) {
  auto fail = [&err](const std::string& message) {
    err << "fleetmap render: " << message << "\n";
    return kExitBadInput;
  };
  const bool svg = HasExtension(options.output, ".svg");
  if (!svg && !HasExtension(options.output, ".png")) {
    return fail(options.output + ": unknown picture format (expected .svg or .png)");
  }
  Status status;
  if (HasExtension(options.input, ".vmap")) {
    status = RenderVmap(options, svg);
  } else if (HasExtension(options.input, ".yaml") || HasExtension(options.input, ".yml")) {
    if (!options.like_yaml.empty()) return fail(options.input + ": --like is for .vmap inputs");
    status = RenderGrid(options, svg);
  } else {
    return fail(options.input + ": unknown input format (expected .vmap or a map .yaml)");
  }
  if (!status.ok()) return fail(status.message());
  out << options.input << " -> " << options.output << "\n";
  out.flush();
  return out ? kExitOk : kExitBadInput;
}

void AddRenderCommand(CLI::App& app, int* exit_code) {
  auto options = std::make_shared<RenderCommandOptions>();
  CLI::App* cmd = app.add_subcommand("render", "Draw a .vmap or a map as SVG or PNG");
  cmd->add_option("input", options->input, ".vmap file or map_server YAML")->required();
  cmd->add_option("-o,--output", options->output, ".svg or .png file to write")->required();
  cmd->add_option("--like", options->like_yaml, "PNG of a .vmap: draw over this map's geometry");
  cmd->add_option("--max-cells", options->max_cells, "Refuse grids with more cells than this")
      ->check(CLI::PositiveNumber);
  cmd->callback([options, exit_code]() { *exit_code = RunRender(*options, std::cout, std::cerr); });
}

}  // namespace fleetmap::cli
