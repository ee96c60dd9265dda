#include "server/fleet_map_log.hpp"

#include <spdlog/spdlog.h>

namespace fleetmap::server {

void LogNotice(const Notice& notice) {
  switch (notice.level) {
    case Notice::Level::kDebug:
      spdlog::debug("server: {}", notice.text);
      return;
    case Notice::Level::kInfo:
      spdlog::info("server: {}", notice.text);
      return;
    case Notice::Level::kWarning:
      spdlog::warn("server: {}", notice.text);
      return;
    case Notice::Level::kError:
      spdlog::error("server: {}", notice.text);
      return;
  }
}

void LogStanding(const fusion::TrustReport& report) {
  if (!report.standing_changed) {
    spdlog::debug("server: robot {} is still quarantined: {}", report.robot.value, report.reason);
  } else if (report.standing == fusion::Standing::kQuarantined) {
    spdlog::warn(
        "server: robot {} quarantined: {}, around ({:.1f}, {:.1f})..({:.1f}, {:.1f}) m; its "
        "tiles are kept, not fused, until its map agrees, another robot confirms the change, or "
        "an operator runs `fleetmap admit {}`",
        report.robot.value, report.reason, report.area_min.x(), report.area_min.y(),
        report.area_max.x(), report.area_max.y(), report.robot.value);
  } else if (report.standing == fusion::Standing::kTrusted) {
    spdlog::info("server: robot {} {}; its tiles are fused again", report.robot.value,
                 report.reason);
  }
}

}  // namespace fleetmap::server
