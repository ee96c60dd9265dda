#pragma once

#include "common/core/notice.hpp"
#include "common/fusion/robot_trust.hpp"

namespace fleetmap::server {

// What the fleet map tells people, in the server's log.
void LogNotice(const Notice& notice);
// A robot that entered or left quarantine (or whose figures moved while in it).
void LogStanding(const fusion::TrustReport& report);

}  // namespace fleetmap::server
