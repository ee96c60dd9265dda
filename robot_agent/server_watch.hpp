#pragma once

#include <chrono>
#include <optional>
#include <string>

namespace fleetmap::agent {

// Tells an agent's operator when no fleet server can be seen: an agent on the wrong DDS domain,
// outside a secured fleet or with its server down publishes into the void without a word
// otherwise. Fed with how many servers (writers of rt/fleetmap/fused_tiles) are matched now; says
// once when none was seen for `patience`, and once when one is seen again. DDS-free, driven by
// the caller's clock.
class ServerWatch {
 public:
  using Clock = std::chrono::steady_clock;

  ServerWatch(std::chrono::milliseconds patience, Clock::time_point start)
      : patience_(patience), last_seen_or_start_(start) {}

  // The line to log now, if any.
  std::optional<std::string> Update(int servers_matched, Clock::time_point now);
  bool missing() const { return reported_missing_; }

 private:
  std::chrono::milliseconds patience_;
  Clock::time_point last_seen_or_start_;
  bool seen_ = false;
  bool reported_missing_ = false;
};

}  // namespace fleetmap::agent
