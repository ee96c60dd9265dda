#pragma once

#include <string>

namespace fleetmap {

// Something a DDS-free module tells the people running it (the log is its caller's): what
// happened, at what weight. Modules collect notices; the program logs them.
struct Notice {
  enum class Level { kDebug, kInfo, kWarning, kError };
  Level level = Level::kInfo;
  std::string text;
};

}  // namespace fleetmap
