// Writes the fuzz targets' generated seeds: for each target, a folder of inputs made with
// fleetmap's own writers from the maps in tests/data (tiles and .vmap files of real maps, plain
// and zstd geometry, one sample of every topic type, images in the formats the loader reads, PLY
// clouds) and the test data files themselves. Run by the fuzz build; the hand-made seeds are
// checked in under fuzz/corpus/<target>/ instead.
//
//   fleetmap-fuzz-seeds <tests/data folder> <output folder>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "common/core/check.hpp"
#include "common/core/file_io.hpp"
#include "common/extrapolation/entities_json.hpp"
#include "common/extrapolation/ply_reader.hpp"
#include "common/grid/map_io.hpp"
#include "common/transport/internal/cdr_codec.hpp"
#include "common/transport/internal/conversions.hpp"
#include "common/transport/internal/vector_tile_codec.hpp"
#include "common/transport/internal/zstd_frame.hpp"
#include "common/transport/map_update_codec.hpp"
#include "common/transport/tile_payload.hpp"
#include "common/transport/vmap_file.hpp"
#include "common/vector_map/tiled_vector_map.hpp"
#include "fleetmap_msgs/msg/Entity.h"
#include "fleetmap_msgs/msg/ObjectModel.h"
#include "fleetmap_msgs/msg/ObjectTemplate.h"
#include "fleetmap_msgs/msg/RobotFrame.h"
#include "fleetmap_msgs/msg/RouteGraph.h"
#include "fleetmap_msgs/msg/Submap.h"
#include "tf2_msgs/msg/TFMessage.h"

namespace fleetmap {
namespace {

namespace fs = std::filesystem;

// Seeds larger than this are left out: libFuzzer's mutations are slow on large inputs.
constexpr uintmax_t kMaxSeedBytes = 64 << 10;

class SeedWriter {
 public:
  explicit SeedWriter(fs::path root) : root_(std::move(root)) {}

  void Write(const std::string& target, const std::string& name, std::string_view bytes) {
    if (bytes.size() > kMaxSeedBytes) return;
    fs::create_directories(root_ / target);
    const Status written = WriteFileAtomically((root_ / target / name).string(), bytes);
    FLEETMAP_CHECK(written.ok(), written.message());
    ++count_;
  }
  void Write(const std::string& target, const std::string& name,
             const std::vector<uint8_t>& bytes) {
    Write(target, name,
          std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
  }
  void Copy(const std::string& target, const fs::path& file) {
    if (fs::file_size(file) > kMaxSeedBytes) return;
    fs::create_directories(root_ / target);
    fs::copy_file(file, root_ / target / file.filename(), fs::copy_options::overwrite_existing);
    ++count_;
  }
  int count() const { return count_; }

 private:
  fs::path root_;
  int count_ = 0;
};

// A CDR sample of a topic type for cdr_samples_fuzzer: its type byte, then the payload.
template <typename Generated>
void WriteSample(SeedWriter& seeds, uint8_t type, const std::string& name,
                 const Generated& sample) {
  seeds.Write("cdr_samples", name,
              std::string(1, static_cast<char>(type)) + transport::SerializeCdr(sample));
}

void WriteTiles(SeedWriter& seeds, const std::string& map_name,
                const vector_map::TiledVectorMap& map) {
  const StatusOr<std::string> vmap = transport::EncodeVmap(map);
  FLEETMAP_CHECK(vmap.ok(), vmap.status().message());
  seeds.Write("vmap", map_name + ".vmap", *vmap);
  int written = 0;
  for (const auto& [id, tile] : map.tiles) {
    if (written++ == 6) break;
    const transport::VectorTileMessage message{RobotId{"alpha"}, id,  7, Timestamp(),
                                               map.tile_size,    tile};
    const StatusOr<std::string> payload = transport::EncodeTilePayload(message);
    FLEETMAP_CHECK(payload.ok(), payload.status().message());
    const std::string name = map_name + "_" + std::to_string(id.x) + "_" + std::to_string(id.y);
    seeds.Write("tile_payload", name, *payload);
    seeds.Write("cdr_samples", "tile_" + name, std::string(1, '\0') + *payload);

    // The geometry string as tile_geometry_fuzzer takes it: mode (plain / zstd), sizes (10 m
    // tiles at 5 cm), the key, then the uncompressed varints.
    const auto sample = transport::ToIdl(message);
    FLEETMAP_CHECK(sample.ok(), sample.status().message());
    std::vector<uint8_t> geometry = sample->geometry();
    if (sample->compression() == 1) {
      auto plain = transport::ZstdDecompress(geometry, size_t{1} << 24, "seed");
      FLEETMAP_CHECK(plain.ok(), plain.status().message());
      geometry = *plain;
    }
    std::string input;
    input.push_back(static_cast<char>(sample->compression()));
    input.push_back('\0');
    input.push_back(static_cast<char>(id.x));
    input.push_back(static_cast<char>(id.y));
    input.append(geometry.begin(), geometry.end());
    seeds.Write("tile_geometry", name, input);
  }
}

void WriteMapSeeds(SeedWriter& seeds, const fs::path& data) {
  for (const char* yaml :
       {"maps/trinary_4x3.yaml", "extrapolation/corridor.yaml", "maps/real/tb3_world.yaml"}) {
    const StatusOr<grid::LoadedMap> map = grid::LoadMap((data / yaml).string());
    FLEETMAP_CHECK(map.ok(), map.status().message());
    const StatusOr<vector_map::TiledVectorMap> tiled =
        vector_map::VectorizeTiled(map->grid, Transform2::Identity());
    FLEETMAP_CHECK(tiled.ok(), tiled.status().message());
    WriteTiles(seeds, fs::path(yaml).stem().string(), *tiled);
  }
  for (const auto& entry : fs::recursive_directory_iterator(data)) {
    const std::string ext = entry.path().extension().string();
    if (ext == ".pgm" || ext == ".png") seeds.Copy("map_image", entry.path());
    if (ext == ".yaml") seeds.Copy("map_yaml", entry.path());
    if (ext == ".json") seeds.Copy("entities_json", entry.path());
  }
  // The formats the loader reads with OpenCV, as OpenCV writes them.
  cv::Mat gray(3, 4, CV_8UC1, cv::Scalar(254));
  gray.at<uint8_t>(1, 1) = 0;
  gray.at<uint8_t>(2, 3) = 205;
  cv::Mat gray16;
  gray.convertTo(gray16, CV_16U, 257.0);
  cv::Mat color;
  cv::merge(std::vector<cv::Mat>{gray, gray, gray}, color);
  cv::Mat rgba;
  cv::merge(std::vector<cv::Mat>{gray, gray, gray, gray}, rgba);
  const std::vector<std::pair<std::string, cv::Mat>> images = {
      {"gray.bmp", gray},     {"color.bmp", color}, {"rgba.bmp", rgba},
      {"gray16.png", gray16}, {"color.png", color}, {"rgba.png", rgba}};
  for (const auto& [name, image] : images) {
    std::vector<uint8_t> bytes;
    FLEETMAP_CHECK(cv::imencode(fs::path(name).extension().string(), image, bytes));
    seeds.Write("map_image", name, bytes);
  }
}

void WriteSampleSeeds(SeedWriter& seeds) {
  RobotStatus status;
  status.robot = RobotId{"alpha"};
  status.map_topic = "rt/alpha/map";
  WriteSample(seeds, 1, "robot_status", transport::ToIdl(status));

  transport::MapMessage grid;
  grid.grid = grid::OccupancyGrid(4, 3, 0.05, Pose2{});
  grid.grid.at(1, 1) = 100;
  WriteSample(seeds, 2, "occupancy_grid", transport::ToIdl(grid));

  transport::MapUpdate update;
  update.x = 1;
  update.width = 2;
  update.height = 2;
  update.data = {0, 100, -1, 0};
  WriteSample(seeds, 3, "occupancy_grid_update", transport::ToIdl(update));
  const StatusOr<transport::CompressedMapUpdate> compressed =
      transport::CompressMapUpdate(update, 3);
  FLEETMAP_CHECK(compressed.ok(), compressed.status().message());
  WriteSample(seeds, 4, "compressed_grid_update", transport::ToIdl(*compressed));

  WriteSample(seeds, 5, "entity", fleetmap_msgs::msg::dds_::Entity_());
  WriteSample(seeds, 6, "submap", fleetmap_msgs::msg::dds_::Submap_());
  WriteSample(seeds, 7, "object_template", fleetmap_msgs::msg::dds_::ObjectTemplate_());
  WriteSample(seeds, 8, "object_model", fleetmap_msgs::msg::dds_::ObjectModel_());
  WriteSample(seeds, 9, "robot_frame", fleetmap_msgs::msg::dds_::RobotFrame_());
  tf2_msgs::msg::dds_::TFMessage_ tf;
  tf.transforms().resize(2);
  tf.transforms()[0].header().frame_id("fleet");
  tf.transforms()[0].child_frame_id("alpha/map");
  fleetmap_msgs::msg::dds_::RouteGraph_ route_graph;
  route_graph.graph_id("fleet");
  route_graph.frame("map");
  route_graph.node_id({1, 2});
  route_graph.node_x({0.0, 2.0});
  route_graph.node_y({0.0, 1.0});
  route_graph.node_kind({1, 1});
  route_graph.node_clearance({0.4F, 0.4F});
  route_graph.edge_id({3});
  route_graph.edge_reverse_id({4});
  route_graph.edge_start({1});
  route_graph.edge_end({2});
  route_graph.edge_length({2.2F});
  route_graph.edge_clearance({0.35F});
  route_graph.node_flags({0, 1});
  route_graph.edge_flags({3});
  route_graph.edge_object({7});
  WriteSample(seeds, 10, "route_graph", route_graph);
  WriteSample(seeds, 11, "tf", tf);
}

void WritePlySeeds(const fs::path& out) {
  const extrapolation::PointCloud cloud = {{0.0, 0.0, 0.0}, {1.5, -2.0, 0.25}, {3.0, 1.0, 2.0}};
  fs::create_directories(out / "ply");
  for (const bool ascii : {false, true}) {
    const std::string path = (out / "ply" / (ascii ? "ascii.ply" : "binary.ply")).string();
    const Status written = extrapolation::WritePly(cloud, path, ascii);
    FLEETMAP_CHECK(written.ok(), written.message());
  }
}

void WriteEntitySeeds(SeedWriter& seeds) {
  scene::Entities entities;
  scene::DoorEntity door;
  door.id = "door-1";
  door.latch = Point2(0.9, 0.0);
  entities.doors.push_back(door);
  scene::StairsEntity stairs;
  stairs.id = "stairs-1";
  stairs.run_length = 2.0;
  entities.stairs.push_back(stairs);
  seeds.Write("entities_json", "written.json", extrapolation::EntitiesToJson(entities));
}

}  // namespace
}  // namespace fleetmap

int main(int argc, char** argv) {
  using namespace fleetmap;
  if (argc != 3) {
    std::fprintf(stderr, "usage: %s <tests/data folder> <output folder>\n", argv[0]);
    return 2;
  }
  const std::filesystem::path out(argv[2]);
  SeedWriter seeds(out);
  WriteMapSeeds(seeds, argv[1]);
  WriteSampleSeeds(seeds);
  WritePlySeeds(out);
  WriteEntitySeeds(seeds);
  std::printf("fleetmap-fuzz-seeds: %d seeds in %s\n", seeds.count() + 2, argv[2]);
  return 0;
}
