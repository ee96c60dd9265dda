#pragma once

// ROS map_server maps (a YAML file naming an image) read and written with the semantics of
// nav2_map_server's map_io (loadMapFromFile / saveMapToFile). docs/file-formats.md is the
// user-facing description; the rules that differ from nav2 (limits, path checks, strict
// validation, refusing a save that would not read back) are stated there and below.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "common/core/options_printer.hpp"
#include "common/core/status.hpp"
#include "common/core/types.hpp"
#include "common/grid/occupancy_grid.hpp"

namespace fleetmap::grid {

// How image shades become cell values (the YAML's `mode`).
enum class MapMode : uint8_t {
  kTrinary,  // 0 free, 100 occupied, -1 unknown (the default)
  kScale,    // as trinary, but shades between the thresholds scale linearly into 0..100
  kRaw,      // the 8-bit shade is the value; shades above 100 are unknown
};

// "trinary", "scale", "raw".
std::string_view MapModeName(MapMode mode);
// The mode of a YAML `mode` string (exact, lowercase), or nothing.
std::optional<MapMode> MapModeFromName(std::string_view name);

// A map YAML's content. Thresholds are probabilities in [0, 1] with free < occupied.
struct MapMetadata {
  std::string image;         // as written in the YAML
  std::string image_path;    // the file actually read: relative to the YAML's directory
  double resolution = 0.05;  // metres per cell
  Pose2 origin;              // map-frame pose of the lower-left corner of the lower-left cell
  MapMode mode = MapMode::kTrinary;
  bool negate = false;
  double occupied_thresh = 0.65;
  double free_thresh = 0.196;
};

struct MapLoadOptions {
  // Images with more cells than this fail with kResourceExhausted before their pixels are read.
  int64_t max_cells = 400'000'000;
  // Likewise images whose decoded pixels take more bytes than this (width * height * channels *
  // bytes per sample, as the decoder holds them, read from the file's header): a small PNG can
  // hold a large image, and a 16-bit RGBA one decodes to 8 bytes per cell. 256 MiB is 268 million
  // cells of an 8-bit gray PNG, or 134 million of a PGM (read into 16-bit samples).
  int64_t max_decoded_bytes = int64_t{256} << 20;
  // nav2 reads any path the YAML names. fleetmap refuses, by default, an image that is not inside
  // the YAML's directory (`../x.pgm`, or an absolute path elsewhere): maps travel between robots
  // and machines, and a map file should not make a server open arbitrary files. The check is
  // lexical (symbolic links inside the directory are followed).
  bool allow_outside_dir = false;

  void Describe(OptionsPrinter& out) const;
};

// A grid with the metadata it was read with (`fleetmap info` prints both).
struct LoadedMap {
  OccupancyGrid grid;
  MapMetadata metadata;
};

// Reads and validates a map YAML; resolves `image_path`. Errors name the YAML file: kNotFound
// (no file), kInvalidArgument (syntax error, missing or bad key, image outside the directory).
StatusOr<MapMetadata> ReadMapYaml(const std::string& yaml_path, const MapLoadOptions& options = {});

// Reads `metadata.image_path` (PGM with fleetmap's own reader; PNG and BMP with OpenCV, after
// their header was checked against the limits; other formats are refused) and converts it with
// the metadata's mode, negate and thresholds. Grid row 0 is the image's bottom row. Errors name
// the image file.
StatusOr<OccupancyGrid> LoadMapImage(const MapMetadata& metadata,
                                     const MapLoadOptions& options = {});

// ReadMapYaml then LoadMapImage.
StatusOr<LoadedMap> LoadMap(const std::string& yaml_path, const MapLoadOptions& options = {});

// The cell value of one pixel, as nav2 computes it. `shade` is the pixel's brightness in [0, 1]
// (channels averaged, alpha included in trinary mode), `opaque` false for a pixel with alpha below
// its maximum (unknown in scale mode).
int8_t CellValueFromShade(double shade, bool opaque, const MapMetadata& metadata);

struct MapSaveOptions {
  MapMode mode = MapMode::kTrinary;
  // Written to the YAML and used to classify values in trinary mode. The defaults make the three
  // trinary shades (0, 205, 254) read back as occupied, unknown and free.
  double occupied_thresh = 0.65;
  double free_thresh = 0.196;
  // "pgm" or "png"; empty picks png for scale mode (it needs alpha for unknown cells) and pgm
  // otherwise, as nav2's map_saver does.
  std::string image_format;
};

// Writes `yaml_path` and, next to it, the image `<stem>.<format>`, like nav2's map_saver: trinary
// writes 0 / 205 / 254, scale writes (100 - v) / 100 gray (unknown transparent), raw writes v
// (unknown 255). Refuses (kInvalidArgument) an empty grid, bad thresholds, thresholds under which
// the trinary shades would not read back as written, and a scale-mode PGM of a grid with unknown
// cells (PGM has no alpha). The YAML's numbers are clean (CleanNumber): the resolution the user
// gave (0.05), origins without arithmetic's float noise. Each file is written whole or not at all
// (WriteFileAtomically); the image goes first, so a YAML on disk never names a missing image.
Status SaveMap(const OccupancyGrid& grid, const std::string& yaml_path,
               const MapSaveOptions& options = {});

}  // namespace fleetmap::grid
