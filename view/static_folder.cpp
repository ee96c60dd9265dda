#include "view/static_folder.hpp"

#include <fmt/format.h>

#include <cstdlib>
#include <filesystem>

namespace fleetmap::view {
namespace {

namespace fs = std::filesystem;

bool HoldsPage(const fs::path& folder) {
  std::error_code error;
  return fs::is_regular_file(folder / "index.html", error);
}

}  // namespace

StatusOr<std::string> FindStaticFolder(const std::string& requested) {
  if (!requested.empty()) {
    if (HoldsPage(requested)) return requested;
    return NotFoundError(fmt::format("--static-dir {}: no index.html there", requested));
  }
  if (const char* from_environment = std::getenv("FLEETMAP_VIEW_DIR")) {
    if (HoldsPage(from_environment)) return std::string(from_environment);
    return NotFoundError(
        fmt::format("$FLEETMAP_VIEW_DIR {}: no index.html there", from_environment));
  }
  std::error_code error;
  const fs::path program = fs::read_symlink("/proc/self/exe", error);
  const fs::path beside =
      (program.parent_path().parent_path() / "share" / "fleetmap" / "view").lexically_normal();
  if (!error && HoldsPage(beside)) return beside.string();
  return NotFoundError(fmt::format(
      "the view's page is not installed: no index.html in {} (build the fleetmap_view_page "
      "target, or give --static-dir)",
      beside.string()));
}

}  // namespace fleetmap::view
