#include "common/grid/map_io.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <system_error>
#include <vector>

#include "common/core/file_io.hpp"
#include "common/core/number_format.hpp"
#include "common/grid/image_file.hpp"
#include "common/grid/image_header.hpp"
#include "common/grid/pgm.hpp"

namespace fleetmap::grid {
namespace {

namespace fs = std::filesystem;

// The three shades nav2's map_saver writes in trinary mode.
constexpr uint8_t kOccupiedShade = 0;
constexpr uint8_t kUnknownShade = 205;
constexpr uint8_t kFreeShade = 254;

std::string ToLower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

Status ValidateThresholds(double occupied_thresh, double free_thresh, const std::string& name) {
  if (!std::isfinite(occupied_thresh) || occupied_thresh < 0.0 || occupied_thresh > 1.0) {
    return InvalidArgumentError(name + ": occupied_thresh must be in [0, 1], got " +
                                ExactNumber(occupied_thresh));
  }
  if (!std::isfinite(free_thresh) || free_thresh < 0.0 || free_thresh > 1.0) {
    return InvalidArgumentError(name + ": free_thresh must be in [0, 1], got " +
                                ExactNumber(free_thresh));
  }
  if (free_thresh >= occupied_thresh) {
    return InvalidArgumentError(name + ": free_thresh (" + ExactNumber(free_thresh) +
                                ") must be below occupied_thresh (" + ExactNumber(occupied_thresh) +
                                ")");
  }
  return Status::Ok();
}

Status ValidateMetadata(const MapMetadata& metadata, const std::string& name) {
  if (!std::isfinite(metadata.resolution) || metadata.resolution <= 0.0) {
    return InvalidArgumentError(name + ": resolution must be a finite number > 0, got " +
                                ExactNumber(metadata.resolution));
  }
  if (!std::isfinite(metadata.origin.x) || !std::isfinite(metadata.origin.y) ||
      !std::isfinite(metadata.origin.yaw)) {
    return InvalidArgumentError(name + ": origin must be finite");
  }
  return ValidateThresholds(metadata.occupied_thresh, metadata.free_thresh, name);
}

// Reads the keys of a parsed map YAML, each error naming the file, the key and its line.
class YamlReader {
 public:
  YamlReader(const YAML::Node& root, const std::string& name) : root_(root), name_(name) {}

  Status Error(const YAML::Node& node, const std::string& problem) const {
    const YAML::Mark mark = node.Mark();
    std::string where = name_;
    if (!mark.is_null()) where += ": line " + std::to_string(mark.line + 1);
    return InvalidArgumentError(where + ": " + problem);
  }
  Status Missing(const char* key) const {
    return InvalidArgumentError(name_ + ": missing required key '" + key + "'");
  }

  std::optional<YAML::Node> Find(const char* key) const {
    const YAML::Node node = root_[key];
    if (!node.IsDefined()) return std::nullopt;
    return node;
  }

  StatusOr<double> Number(const YAML::Node& node, const std::string& what) const {
    double value = 0.0;
    if (!node.IsScalar() || !YAML::convert<double>::decode(node, value)) {
      return Error(node, what + " must be a number, got " + Show(node));
    }
    if (!std::isfinite(value)) return Error(node, what + " must be finite, got " + Show(node));
    return value;
  }

  StatusOr<double> RequiredNumber(const char* key) const {
    const auto node = Find(key);
    if (!node) return Missing(key);
    return Number(*node, key);
  }

  static std::string Show(const YAML::Node& node) {
    if (node.IsScalar()) return "'" + node.Scalar() + "'";
    if (node.IsSequence()) return "a list of " + std::to_string(node.size()) + " items";
    if (node.IsMap()) return "a mapping";
    return "nothing";
  }

 private:
  const YAML::Node& root_;
  const std::string& name_;
};

// Resolves the YAML's `image` against the YAML's directory and applies the directory rule.
StatusOr<std::string> ResolveImagePath(const std::string& yaml_path, const std::string& image,
                                       const MapLoadOptions& options) {
  const fs::path yaml_dir = fs::path(yaml_path).parent_path();
  const fs::path image_path(image);
  const fs::path resolved = image_path.is_absolute() ? image_path : yaml_dir / image_path;
  if (!options.allow_outside_dir) {
    std::error_code error;
    const fs::path base = fs::absolute(yaml_dir.empty() ? fs::path(".") : yaml_dir, error);
    const fs::path target = fs::absolute(resolved, error);
    if (error) return InvalidArgumentError(yaml_path + ": cannot resolve image '" + image + "'");
    const fs::path relative = target.lexically_normal().lexically_relative(base.lexically_normal());
    if (relative.empty() || *relative.begin() == "..") {
      return InvalidArgumentError(
          yaml_path + ": image '" + image +
          "' is outside the YAML's directory; fleetmap reads only images inside it "
          "(allow_outside_dir / --allow-outside-dir lifts this)");
    }
  }
  return resolved.string();
}

// Reads the first bytes of a file, to pick a decoder by content.
std::string FileHead(const std::string& path, size_t count) {
  std::ifstream in(path, std::ios::binary);
  std::string head(count, '\0');
  in.read(head.data(), static_cast<std::streamsize>(count));
  head.resize(static_cast<size_t>(std::max<std::streamsize>(in.gcount(), 0)));
  return head;
}

bool LooksLikePgm(const std::string& path, const std::string& head) {
  if (ToLower(fs::path(path).extension().string()) == ".pgm") return true;
  return head.size() >= 2 && head[0] == 'P' && (head[1] == '2' || head[1] == '5');
}

OccupancyGrid MakeGrid(int width, int height, const MapMetadata& metadata) {
  return OccupancyGrid(width, height, metadata.resolution, metadata.origin);
}

StatusOr<OccupancyGrid> LoadPgmImage(const MapMetadata& metadata, const MapLoadOptions& options) {
  PgmReadOptions pgm_options;
  pgm_options.max_cells = options.max_cells;
  pgm_options.max_decoded_bytes = options.max_decoded_bytes;
  FLEETMAP_ASSIGN_OR_RETURN(const PgmImage image, ReadPgm(metadata.image_path, pgm_options));
  // A PGM has one channel and no alpha: the cell value depends on the sample alone.
  std::vector<int8_t> lut(static_cast<size_t>(image.max_value) + 1);
  for (int v = 0; v <= image.max_value; ++v) {
    lut[v] = CellValueFromShade(static_cast<double>(v) / image.max_value, true, metadata);
  }
  OccupancyGrid grid = MakeGrid(image.width, image.height, metadata);
  for (int row = 0; row < image.height; ++row) {
    const int y = image.height - 1 - row;  // image row 0 is the top, grid row 0 the bottom
    for (int x = 0; x < image.width; ++x) grid.at(x, y) = lut[image.at(x, row)];
  }
  return grid;
}

template <typename Sample>
void ConvertMat(const cv::Mat& mat, double max_value, const MapMetadata& metadata,
                OccupancyGrid* grid) {
  const int channels = mat.channels();
  const bool has_alpha = channels == 2 || channels == 4;
  for (int row = 0; row < mat.rows; ++row) {
    const Sample* pixel = mat.ptr<Sample>(row);
    const int y = mat.rows - 1 - row;
    for (int x = 0; x < mat.cols; ++x, pixel += channels) {
      // Gray counts as three equal colour channels, as ImageMagick reports it to nav2.
      const double color_sum =
          channels >= 3 ? static_cast<double>(pixel[0]) + pixel[1] + pixel[2] : 3.0 * pixel[0];
      const double alpha = has_alpha ? pixel[channels - 1] : max_value;
      double average = color_sum / 3.0;
      // nav2 averages alpha into the colour channels in trinary mode ("to preserve behaviour").
      if (has_alpha && metadata.mode == MapMode::kTrinary) average = (color_sum + alpha) / 4.0;
      grid->at(x, y) = CellValueFromShade(average / max_value, alpha >= max_value, metadata);
    }
  }
}

StatusOr<OccupancyGrid> LoadOtherImage(const MapMetadata& metadata, const MapLoadOptions& options) {
  const std::string& path = metadata.image_path;
  // OpenCV allocates the whole decoded image at once, as the header describes it: check first.
  FLEETMAP_ASSIGN_OR_RETURN(const ImageHeader header, ReadImageHeader(path));
  FLEETMAP_RETURN_IF_ERROR(header.CheckLimits(path, options.max_cells, options.max_decoded_bytes));
  cv::Mat mat;
  try {
    mat = cv::imread(path, cv::IMREAD_UNCHANGED);
  } catch (const cv::Exception& e) {
    return DataLossError(path + ": cannot decode image: " + e.what());
  }
  if (mat.empty()) {
    return DataLossError(path + ": cannot decode the " + header.format +
                         " image (truncated or corrupt)");
  }
  if (mat.cols != header.width || mat.rows != header.height) {
    // The file changed between the header and the pixels (it is being rewritten).
    return DataLossError(path + ": decoded " + std::to_string(mat.cols) + " x " +
                         std::to_string(mat.rows) + " pixels, the header said " +
                         std::to_string(header.width) + " x " + std::to_string(header.height));
  }
  if (mat.dims != 2 || mat.channels() > 4) {
    return InvalidArgumentError(path + ": unsupported image layout (" +
                                std::to_string(mat.channels()) + " channels)");
  }
  OccupancyGrid grid = MakeGrid(mat.cols, mat.rows, metadata);
  switch (mat.depth()) {
    case CV_8U:
      ConvertMat<uint8_t>(mat, 255.0, metadata, &grid);
      break;
    case CV_16U:
      ConvertMat<uint16_t>(mat, 65535.0, metadata, &grid);
      break;
    default:
      return InvalidArgumentError(path + ": unsupported sample depth (only 8 and 16 bit)");
  }
  return grid;
}

// One row of pixels of a saved image, top row first.
uint8_t TrinaryShade(int8_t value, int free_int, int occupied_int) {
  if (value < 0 || value > 100) return kUnknownShade;
  if (value <= free_int) return kFreeShade;
  if (value >= occupied_int) return kOccupiedShade;
  return kUnknownShade;
}

uint8_t ScaleShade(int8_t value) {
  return static_cast<uint8_t>(std::lround((100.0 - value) * 255.0 / 100.0));
}

uint8_t RawShade(int8_t value) {
  return value < 0 || value > 100 ? 255 : static_cast<uint8_t>(value);
}

// Refuses thresholds under which a trinary shade written by SaveMap would read back differently.
Status CheckTrinaryReadBack(const OccupancyGrid& grid, const MapSaveOptions& options,
                            const std::string& name) {
  const int free_int = static_cast<int>(std::rint(options.free_thresh * 100.0));
  const int occupied_int = static_cast<int>(std::rint(options.occupied_thresh * 100.0));
  std::array<bool, 256> used{};
  for (const int8_t value : grid.data()) used[TrinaryShade(value, free_int, occupied_int)] = true;
  MapMetadata read_back;
  read_back.occupied_thresh = options.occupied_thresh;
  read_back.free_thresh = options.free_thresh;
  const std::array<std::pair<uint8_t, int8_t>, 3> expected = {
      {{kOccupiedShade, kOccupiedValue}, {kUnknownShade, kUnknownValue}, {kFreeShade, kFreeValue}}};
  for (const auto& [shade, value] : expected) {
    if (!used[shade]) continue;
    const int8_t got = CellValueFromShade(shade / 255.0, true, read_back);
    if (got != value) {
      return InvalidArgumentError(name + ": with occupied_thresh " +
                                  ExactNumber(options.occupied_thresh) + " and free_thresh " +
                                  ExactNumber(options.free_thresh) + ", the trinary shade " +
                                  std::to_string(shade) + " would read back as " +
                                  std::to_string(got) + " instead of " + std::to_string(value) +
                                  " (free_thresh must be in (1/255, 50/255], occupied_thresh in "
                                  "[50/255, 1))");
    }
  }
  return Status::Ok();
}

Status WriteYaml(const OccupancyGrid& grid, const std::string& yaml_path,
                 const std::string& image_name, const MapSaveOptions& options) {
  YAML::Emitter out;
  out << YAML::BeginMap;
  out << YAML::Key << "image" << YAML::Value << image_name;
  out << YAML::Key << "mode" << YAML::Value << std::string(MapModeName(options.mode));
  // Clean numbers: the resolution the user gave ("0.05"), an origin without arithmetic's noise.
  out << YAML::Key << "resolution" << YAML::Value << CleanNumber(grid.resolution());
  out << YAML::Key << "origin" << YAML::Value << YAML::Flow << YAML::BeginSeq
      << CleanNumber(grid.origin().x) << CleanNumber(grid.origin().y)
      << CleanNumber(grid.origin().yaw) << YAML::EndSeq;
  out << YAML::Key << "negate" << YAML::Value << 0;
  out << YAML::Key << "occupied_thresh" << YAML::Value << CleanNumber(options.occupied_thresh);
  out << YAML::Key << "free_thresh" << YAML::Value << CleanNumber(options.free_thresh);
  out << YAML::EndMap;
  if (!out.good()) return InternalError(yaml_path + ": YAML emitter failed: " + out.GetLastError());
  return WriteFileAtomically(yaml_path, std::string(out.c_str()) + "\n");
}

}  // namespace

std::string_view MapModeName(MapMode mode) {
  switch (mode) {
    case MapMode::kTrinary:
      return "trinary";
    case MapMode::kScale:
      return "scale";
    case MapMode::kRaw:
      return "raw";
  }
  return "unknown";
}

std::optional<MapMode> MapModeFromName(std::string_view name) {
  for (const MapMode mode : {MapMode::kTrinary, MapMode::kScale, MapMode::kRaw}) {
    if (MapModeName(mode) == name) return mode;
  }
  return std::nullopt;
}

int8_t CellValueFromShade(double shade, bool opaque, const MapMetadata& metadata) {
  const double occ = metadata.negate ? shade : 1.0 - shade;
  switch (metadata.mode) {
    case MapMode::kTrinary:
      if (metadata.occupied_thresh < occ) return kOccupiedValue;
      if (occ < metadata.free_thresh) return kFreeValue;
      return kUnknownValue;
    case MapMode::kScale:
      if (!opaque) return kUnknownValue;
      if (metadata.occupied_thresh < occ) return kOccupiedValue;
      if (occ < metadata.free_thresh) return kFreeValue;
      return static_cast<int8_t>(std::rint((occ - metadata.free_thresh) /
                                           (metadata.occupied_thresh - metadata.free_thresh) *
                                           100.0));
    case MapMode::kRaw: {
      // Raw ignores negate and thresholds, as in nav2.
      const double value = std::round(shade * 255.0);
      if (value >= 0.0 && value <= 100.0) return static_cast<int8_t>(value);
      return kUnknownValue;
    }
  }
  return kUnknownValue;
}

StatusOr<MapMetadata> ReadMapYaml(const std::string& yaml_path, const MapLoadOptions& options) {
  std::error_code error;
  const fs::file_status file_status = fs::status(yaml_path, error);
  if (!fs::exists(file_status)) return NotFoundError(yaml_path + ": no such file");
  if (!fs::is_regular_file(file_status)) {
    return InvalidArgumentError(yaml_path + ": is not a regular file, expected a map YAML file");
  }
  // A map YAML is a few hundred bytes; refuse to parse something enormous by mistake.
  constexpr uintmax_t kMaxYamlBytes = 1 << 20;
  const uintmax_t yaml_bytes = fs::file_size(yaml_path, error);
  if (!error && yaml_bytes > kMaxYamlBytes) {
    return ResourceExhaustedError(yaml_path + ": YAML file is " + std::to_string(yaml_bytes) +
                                  " bytes, more than the limit of " +
                                  std::to_string(kMaxYamlBytes));
  }
  YAML::Node root;
  try {
    root = YAML::LoadFile(yaml_path);
  } catch (const YAML::ParserException& e) {
    return InvalidArgumentError(yaml_path + ": YAML syntax error at line " +
                                std::to_string(e.mark.line + 1) + ", column " +
                                std::to_string(e.mark.column + 1) + ": " + e.msg);
  } catch (const YAML::Exception& e) {
    return InvalidArgumentError(yaml_path + ": cannot read YAML: " + e.what());
  }
  if (!root.IsMap()) {
    return InvalidArgumentError(yaml_path +
                                ": expected a YAML mapping with the keys image, "
                                "resolution, origin, negate, occupied_thresh, free_thresh");
  }
  const YamlReader reader(root, yaml_path);
  MapMetadata metadata;

  const auto image = reader.Find("image");
  if (!image) return reader.Missing("image");
  if (!image->IsScalar() || image->Scalar().empty()) {
    return reader.Error(*image,
                        "image must be a non-empty file name, got " + YamlReader::Show(*image));
  }
  metadata.image = image->Scalar();
  FLEETMAP_ASSIGN_OR_RETURN(metadata.image_path,
                            ResolveImagePath(yaml_path, metadata.image, options));

  FLEETMAP_ASSIGN_OR_RETURN(metadata.resolution, reader.RequiredNumber("resolution"));
  if (metadata.resolution <= 0.0) {
    return reader.Error(*reader.Find("resolution"), "resolution must be > 0 metres per cell, got " +
                                                        ExactNumber(metadata.resolution));
  }

  const auto origin = reader.Find("origin");
  if (!origin) return reader.Missing("origin");
  if (!origin->IsSequence() || origin->size() != 3) {
    return reader.Error(*origin, "origin must be a list of 3 numbers [x, y, yaw], got " +
                                     YamlReader::Show(*origin));
  }
  FLEETMAP_ASSIGN_OR_RETURN(metadata.origin.x, reader.Number((*origin)[0], "origin x"));
  FLEETMAP_ASSIGN_OR_RETURN(metadata.origin.y, reader.Number((*origin)[1], "origin y"));
  FLEETMAP_ASSIGN_OR_RETURN(metadata.origin.yaw, reader.Number((*origin)[2], "origin yaw"));

  const auto negate = reader.Find("negate");
  if (!negate) return reader.Missing("negate");
  int negate_int = 0;
  bool negate_bool = false;
  if (negate->IsScalar() && YAML::convert<int>::decode(*negate, negate_int) &&
      (negate_int == 0 || negate_int == 1)) {
    metadata.negate = negate_int == 1;
  } else if (negate->IsScalar() && YAML::convert<bool>::decode(*negate, negate_bool)) {
    metadata.negate = negate_bool;
  } else {
    return reader.Error(*negate, "negate must be 0 or 1, got " + YamlReader::Show(*negate));
  }

  FLEETMAP_ASSIGN_OR_RETURN(metadata.occupied_thresh, reader.RequiredNumber("occupied_thresh"));
  FLEETMAP_ASSIGN_OR_RETURN(metadata.free_thresh, reader.RequiredNumber("free_thresh"));
  FLEETMAP_RETURN_IF_ERROR(
      ValidateThresholds(metadata.occupied_thresh, metadata.free_thresh, yaml_path));

  if (const auto mode = reader.Find("mode")) {
    const std::optional<MapMode> parsed =
        mode->IsScalar() ? MapModeFromName(mode->Scalar()) : std::nullopt;
    if (!parsed) {
      return reader.Error(
          *mode, "unknown mode " + YamlReader::Show(*mode) + ", expected trinary, scale or raw");
    }
    metadata.mode = *parsed;
  }
  return metadata;
}

StatusOr<OccupancyGrid> LoadMapImage(const MapMetadata& metadata, const MapLoadOptions& options) {
  const std::string& path = metadata.image_path;
  FLEETMAP_RETURN_IF_ERROR(ValidateMetadata(metadata, path));
  std::error_code error;
  const fs::file_status file_status = fs::status(path, error);
  if (!fs::exists(file_status)) return NotFoundError(path + ": no such file");
  if (!fs::is_regular_file(file_status)) {
    return InvalidArgumentError(path + ": is not a regular file, expected an image");
  }
  if (LooksLikePgm(path, FileHead(path, 2))) return LoadPgmImage(metadata, options);
  return LoadOtherImage(metadata, options);
}

StatusOr<LoadedMap> LoadMap(const std::string& yaml_path, const MapLoadOptions& options) {
  LoadedMap map;
  FLEETMAP_ASSIGN_OR_RETURN(map.metadata, ReadMapYaml(yaml_path, options));
  StatusOr<OccupancyGrid> grid = LoadMapImage(map.metadata, options);
  if (!grid.ok()) {
    if (grid.status().code() == StatusCode::kNotFound) {
      return NotFoundError(grid.status().message() + " (the image of " + yaml_path + ")");
    }
    return grid.status();
  }
  map.grid = std::move(grid).value();
  return map;
}

Status SaveMap(const OccupancyGrid& grid, const std::string& yaml_path,
               const MapSaveOptions& options) {
  if (grid.empty()) return InvalidArgumentError(yaml_path + ": cannot save an empty grid");
  FLEETMAP_RETURN_IF_ERROR(
      ValidateThresholds(options.occupied_thresh, options.free_thresh, yaml_path));
  std::string format = ToLower(options.image_format);
  if (format.empty()) format = options.mode == MapMode::kScale ? "png" : "pgm";
  if (format != "pgm" && format != "png") {
    return InvalidArgumentError(yaml_path + ": image format '" + options.image_format +
                                "' is not supported for saving; use pgm or png");
  }
  const fs::path image_path =
      fs::path(yaml_path).parent_path() / (fs::path(yaml_path).stem().string() + "." + format);
  if (image_path == fs::path(yaml_path)) {
    return InvalidArgumentError(yaml_path + ": the YAML path would be overwritten by its image");
  }
  const bool has_unknown = std::any_of(grid.data().begin(), grid.data().end(),
                                       [](int8_t v) { return v < 0 || v > 100; });
  if (options.mode == MapMode::kTrinary) {
    FLEETMAP_RETURN_IF_ERROR(CheckTrinaryReadBack(grid, options, yaml_path));
  }
  if (options.mode == MapMode::kScale && format == "pgm" && has_unknown) {
    return InvalidArgumentError(yaml_path +
                                ": scale mode stores unknown cells as transparent pixels and PGM "
                                "has no alpha channel; save as png");
  }

  const int free_int = static_cast<int>(std::rint(options.free_thresh * 100.0));
  const int occupied_int = static_cast<int>(std::rint(options.occupied_thresh * 100.0));
  const bool with_alpha = options.mode == MapMode::kScale && format == "png";
  cv::Mat mat(grid.height(), grid.width(), with_alpha ? CV_8UC4 : CV_8UC1);
  for (int row = 0; row < grid.height(); ++row) {
    const int y = grid.height() - 1 - row;
    uint8_t* out = mat.ptr<uint8_t>(row);
    for (int x = 0; x < grid.width(); ++x) {
      const int8_t value = grid.at(x, y);
      uint8_t shade = 0;
      switch (options.mode) {
        case MapMode::kTrinary:
          shade = TrinaryShade(value, free_int, occupied_int);
          break;
        case MapMode::kScale:
          shade = value < 0 || value > 100 ? 128 : ScaleShade(value);
          break;
        case MapMode::kRaw:
          shade = RawShade(value);
          break;
      }
      if (with_alpha) {
        const bool unknown = value < 0 || value > 100;
        out[4 * x] = out[4 * x + 1] = out[4 * x + 2] = shade;
        out[4 * x + 3] = unknown ? 0 : 255;
      } else {
        out[x] = shade;
      }
    }
  }

  if (format == "pgm") {
    PgmImage image;
    image.width = grid.width();
    image.height = grid.height();
    image.max_value = 255;
    image.pixels.assign(mat.datastart, mat.dataend);
    FLEETMAP_RETURN_IF_ERROR(WritePgm(image, image_path.string()));
  } else {
    FLEETMAP_RETURN_IF_ERROR(WriteImageFile(image_path.string(), mat));
  }
  return WriteYaml(grid, yaml_path, image_path.filename().string(), options);
}

void MapLoadOptions::Describe(OptionsPrinter& out) const {
  out.Add("max_cells", max_cells);
  out.Add("max_decoded_bytes", max_decoded_bytes);
  out.Add("allow_outside_dir", allow_outside_dir);
}

}  // namespace fleetmap::grid
