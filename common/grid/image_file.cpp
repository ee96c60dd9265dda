#include "common/grid/image_file.hpp"

#include <cstdint>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <vector>

#include "common/core/file_io.hpp"

namespace fleetmap::grid {

Status WriteImageFile(const std::string& path, const cv::Mat& image) {
  const std::string extension = std::filesystem::path(path).extension().string();
  std::vector<uint8_t> bytes;
  try {
    if (!cv::imencode(extension, image, bytes)) {
      return InvalidArgumentError(path + ": cannot encode the image as " + extension);
    }
  } catch (const cv::Exception& e) {
    return InvalidArgumentError(path + ": cannot encode the image as " + extension + ": " +
                                e.what());
  }
  return WriteFileAtomically(path, bytes);
}

}  // namespace fleetmap::grid
