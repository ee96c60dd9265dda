#include "common/config/version.hpp"

#include <fastrtps/config.h>

#include "common/config/build_version.hpp"

namespace fleetmap::config {

std::string_view FleetmapVersion() { return FLEETMAP_VERSION; }

std::string_view GitCommit() { return FLEETMAP_GIT_COMMIT; }

std::string_view FastDdsVersion() { return FASTRTPS_VERSION_STR; }

std::string VersionText(std::string_view program) {
  std::string text(program);
  text.append(" ")
      .append(FleetmapVersion())
      .append(" (commit ")
      .append(GitCommit())
      .append(")\nFast DDS ")
      .append(FastDdsVersion());
  return text;
}

}  // namespace fleetmap::config
