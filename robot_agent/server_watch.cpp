#include "robot_agent/server_watch.hpp"

#include <fmt/format.h>

namespace fleetmap::agent {

std::optional<std::string> ServerWatch::Update(int servers_matched, Clock::time_point now) {
  if (servers_matched > 0) {
    last_seen_or_start_ = now;
    const bool back = reported_missing_;
    const bool first = !seen_;
    seen_ = true;
    reported_missing_ = false;
    if (back) return fmt::format("a fleet server is {} now", first ? "seen" : "back");
    return std::nullopt;
  }
  if (reported_missing_ || now - last_seen_or_start_ < patience_) return std::nullopt;
  reported_missing_ = true;
  const auto seconds = std::chrono::duration_cast<std::chrono::seconds>(patience_).count();
  if (seen_) {
    return fmt::format("the fleet server has been gone for {} s: its map is not fused meanwhile",
                       seconds);
  }
  return fmt::format(
      "no fleet server seen for {} s (no writer of rt/fleetmap/fused_tiles matched): is it "
      "running, on this DDS domain, and with --security if the fleet is secured?",
      seconds);
}

}  // namespace fleetmap::agent
