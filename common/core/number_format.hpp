#pragma once

#include <cstdio>
#include <string>

namespace fleetmap {

// The shortest readable form of a number for messages: 0.05, not 0.050000 (printf's %g).
inline std::string ShortNumber(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%g", value);
  return buffer;
}

}  // namespace fleetmap
