// Fuzz target: a map_server YAML file, loaded whole (`LoadMap`: the YAML, its image path rule,
// then the image with the YAML's mode, negate and thresholds). The scratch folder holds small
// images under the names the seeds use, so a YAML that passes reaches the conversion; a YAML
// naming anything outside the folder is refused before any file is opened.

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include <cstddef>
#include <cstdint>
#include <vector>

#include "common/core/check.hpp"
#include "common/grid/map_io.hpp"
#include "fuzz/fuzz_support.hpp"

namespace {

// A 4 x 3 map of every shade class, as PGM under the seeds' names and as a gray + alpha PNG.
void WriteImages(const std::filesystem::path& folder) {
  const std::string pgm = std::string("P5\n4 3\n255\n") +
                          std::string("\x00\xfe\xcd\x80\xfe\x00\xcd\x10\xff\x7f\x00\xfe", 12);
  for (const char* name : {"map.pgm", "trinary_4x3.pgm", "raw_4x3.pgm", "p2_16bit.pgm",
                           "corridor.pgm", "size_mismatch.pgm", "bad_magic.pgm"}) {
    fleetmap::fuzz::WriteScratchFile(folder / name, pgm);
  }
  cv::Mat image(3, 4, CV_8UC4, cv::Scalar(0, 0, 0, 255));
  image.at<cv::Vec4b>(0, 1) = cv::Vec4b(254, 254, 254, 255);
  image.at<cv::Vec4b>(1, 2) = cv::Vec4b(205, 205, 205, 0);
  std::vector<uint8_t> png;
  FLEETMAP_CHECK(cv::imencode(".png", image, png));
  fleetmap::fuzz::WriteScratchFile(
      folder / "scale_4x3.png",
      std::string_view(reinterpret_cast<const char*>(png.data()), png.size()));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace fleetmap;
  static const std::filesystem::path folder = [] {
    const std::filesystem::path maps = fuzz::ScratchFolder() / "maps";
    std::filesystem::create_directories(maps);
    WriteImages(maps);
    return maps;
  }();
  static const std::string yaml = (folder / "fuzz.yaml").string();
  fuzz::WriteScratchFile(yaml, fuzz::AsText(data, size));
  const StatusOr<grid::LoadedMap> map = grid::LoadMap(yaml);
  if (!map.ok()) return 0;
  FLEETMAP_CHECK(map->metadata.resolution > 0.0);
  FLEETMAP_CHECK(map->metadata.free_thresh < map->metadata.occupied_thresh);
  for (const int8_t value : map->grid.data()) FLEETMAP_CHECK(value >= -1 && value <= 100);
  return 0;
}
