#include "server/refusal_log.hpp"

#include <spdlog/spdlog.h>

namespace fleetmap::server {

const char* RefusalName(Refusal refusal) {
  switch (refusal) {
    case Refusal::kMalformed:
      return "malformed";
    case Refusal::kBadRobotId:
      return "bad robot id";
    case Refusal::kTileOutOfRange:
      return "tile out of range";
    case Refusal::kBadTileSettings:
      return "bad tile settings";
    case Refusal::kStampOutOfWindow:
      return "stamp out of window";
    case Refusal::kTileQuota:
      return "tile quota";
    case Refusal::kByteQuota:
      return "byte quota";
    case Refusal::kNotOwner:
      return "not the owner";
    case Refusal::kUnclaimed:
      return "unclaimed robot id";
    case Refusal::kNotItself:
      return "not its identity";
  }
  return "unknown";
}

void RefusalLog::Refuse(const std::string& robot, Refusal reason, const std::string& detail,
                        std::chrono::steady_clock::time_point now) {
  ++total_;
  std::string key = robot.empty() ? "(unnamed)" : robot;
  // A peer inventing robot ids must not grow this map without bound either.
  if (robots_.size() >= kMaxRobotsTracked && robots_.count(key) == 0) key = "(others)";
  RobotLog& log = robots_[key];
  ++log.counts[reason];
  if (now - log.period_start >= period_) {
    if (log.left_out > 0) {
      spdlog::warn(
          "{}: refused {} more samples from {} in the last {} s without logging each", who_,
          log.left_out, key,
          std::chrono::duration_cast<std::chrono::seconds>(now - log.period_start).count());
    }
    log.period_start = now;
    log.logged.clear();
    log.left_out = 0;
  }
  if (log.logged.count(detail) > 0 || log.logged.size() >= kLinesPerPeriod) {
    ++log.left_out;
    return;
  }
  log.logged.insert(detail);
  spdlog::warn("{}: refused from {} ({}): {}", who_, key, RefusalName(reason), detail);
}

uint64_t RefusalLog::count(const std::string& robot, Refusal reason) const {
  const auto it = robots_.find(robot.empty() ? "(unnamed)" : robot);
  if (it == robots_.end()) return 0;
  const auto count = it->second.counts.find(reason);
  return count == it->second.counts.end() ? 0 : count->second;
}

std::map<std::string, std::map<Refusal, uint64_t>> RefusalLog::counts() const {
  std::map<std::string, std::map<Refusal, uint64_t>> out;
  for (const auto& [robot, log] : robots_) out[robot] = log.counts;
  return out;
}

}  // namespace fleetmap::server
