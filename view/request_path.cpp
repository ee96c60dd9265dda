#include "view/request_path.hpp"

#include <algorithm>

namespace fleetmap::view {

PathRoute RoutePath(std::string_view path) {
  if (path == "/events") return PathRoute::kEvents;
  if (path == "/map.png") return PathRoute::kMapImage;
  if (path.empty() || path.front() != '/') return PathRoute::kNotFound;
  if (path.find("..") != std::string_view::npos || path.find('\\') != std::string_view::npos) {
    return PathRoute::kNotFound;
  }
  const bool control = std::any_of(path.begin(), path.end(), [](char c) {
    const auto byte = static_cast<unsigned char>(c);
    return byte < 0x20 || byte == 0x7f;
  });
  return control ? PathRoute::kNotFound : PathRoute::kStaticFile;
}

}  // namespace fleetmap::view
