#include "common/core/ids.hpp"

#include <cctype>

namespace fleetmap {

std::ostream& operator<<(std::ostream& os, const TileId& id) {
  return os << "tile(" << id.x << ", " << id.y << ")";
}

std::ostream& operator<<(std::ostream& os, const RobotId& id) { return os << id.value; }

bool IsValidRobotName(const std::string& name) {
  constexpr size_t kMaxLength = 64;
  if (name.empty() || name.size() > kMaxLength) return false;
  if (!std::isalpha(static_cast<unsigned char>(name.front()))) return false;
  for (const char c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_') return false;
  }
  return true;
}

}  // namespace fleetmap
