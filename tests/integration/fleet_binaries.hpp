#pragma once

// The fleet's binaries as the integration tests start them: from this build tree.

#include <string>

namespace fleetmap::testing {

inline const std::string kAgentBinary =
    std::string(FLEETMAP_BINARY_DIR) + "/robot_agent/fleetmap-agent";
inline const std::string kServerBinary =
    std::string(FLEETMAP_BINARY_DIR) + "/server/fleetmap-server";

}  // namespace fleetmap::testing
