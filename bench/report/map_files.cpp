#include "bench/report/map_files.hpp"

#include <algorithm>
#include <filesystem>

namespace fleetmap::bench {

StatusOr<std::vector<std::string>> MapFilesIn(const std::string& dir) {
  std::error_code error;
  if (!std::filesystem::is_directory(dir, error)) {
    return NotFoundError(dir + ": no such directory");
  }
  std::vector<std::string> files;
  for (const auto& entry : std::filesystem::directory_iterator(dir, error)) {
    if (entry.path().extension() == ".yaml") files.push_back(entry.path().string());
  }
  if (error) return NotFoundError(dir + ": " + error.message());
  if (files.empty()) return NotFoundError(dir + ": no *.yaml map files");
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace fleetmap::bench
