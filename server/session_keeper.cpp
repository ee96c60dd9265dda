#include "server/session_keeper.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>

namespace fleetmap::server {

Status SessionKeeper::Restore() {
  FLEETMAP_ASSIGN_OR_RETURN(const std::vector<std::string> skipped, archive_.Restore());
  for (const std::string& warning : skipped) {
    spdlog::warn("server: skipping a stored mapping session: {}", warning);
  }
  return Status::Ok();
}

void SessionKeeper::Follow(const fusion::ContributionChange& change) {
  if (change.map) {
    archive_.RecordTile(change.robot, change.tile, *change.map, change.stamp);
  } else {
    archive_.RemoveTile(change.robot, change.tile);
  }
}

void SessionKeeper::Refused(const RobotId& robot, fusion::Refusal reason) {
  if (fusion::CutsTheMap(reason) && archive_.has_open_session(robot)) cut_.insert(robot);
}

std::string SessionKeeper::WhyNotKept(const RobotId& robot, const fusion::FleetMap& map) const {
  if (cut_.count(robot) > 0) {
    return "a budget refused some of its tiles, so the server does not hold its map whole";
  }
  if (map.TrustOf(robot).standing == fusion::Standing::kQuarantined) {
    return "it is quarantined, its map contradicts the fleet's";
  }
  return {};
}

size_t SessionKeeper::RobotsChanged(const std::vector<store::RobotRecord>& records,
                                    const fusion::FleetMap& map) {
  size_t store_errors = 0;
  std::vector<std::string> discarded;
  for (const store::RobotRecord& robot : records) {
    if (robot.state == "active") {
      archive_.Rejoin(robot.robot);
      continue;
    }
    if (const std::string why = WhyNotKept(robot.robot, map); !why.empty()) {
      cut_.erase(robot.robot);
      const size_t tiles = archive_.DiscardSession(robot.robot);
      if (tiles > 0) {
        discarded.push_back(fmt::format("{} ({} tiles: {})", robot.robot.value, tiles, why));
      }
      continue;
    }
    const Timestamp ended{
        std::chrono::duration_cast<Clock::duration>(std::chrono::nanoseconds(robot.last_seen_ns))};
    StatusOr<std::optional<MappingSession>> finished = archive_.EndSession(robot.robot, ended);
    if (!finished.ok()) {
      spdlog::error("server: map store: {}", finished.status().message());
      ++store_errors;
    } else if (!finished->has_value()) {
      continue;
    } else {
      spdlog::info("server: mapping session {} of {} finished ({} tiles)", (**finished).id,
                   robot.robot.value, (**finished).map.tiles.size());
    }
    if (listener_) listener_(archive_.finished());
  }
  if (!discarded.empty()) {
    // One line a round however many ids end: a flood of ids must not flood the log.
    constexpr size_t kNamed = 3;
    const size_t named = std::min(discarded.size(), kNamed);
    spdlog::info(
        "server: {} mapping session(s) not kept for object learning: {}{}", discarded.size(),
        fmt::join(discarded.begin(), discarded.begin() + static_cast<std::ptrdiff_t>(named), "; "),
        discarded.size() > named ? fmt::format(" and {} more", discarded.size() - named)
                                 : std::string());
  }
  return store_errors;
}

}  // namespace fleetmap::server
