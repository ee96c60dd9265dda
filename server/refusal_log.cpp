#include "server/refusal_log.hpp"

#include <spdlog/spdlog.h>

namespace fleetmap::server {

void RefusalLog::Refuse(const std::string& robot, fusion::Refusal reason, const std::string& detail,
                        std::chrono::steady_clock::time_point now) {
  RefuseFrom(std::string(), robot, reason, detail, now);
}

void RefusalLog::RefuseFrom(const std::string& participant, const std::string& robot,
                            fusion::Refusal reason, const std::string& detail,
                            std::chrono::steady_clock::time_point now) {
  ++total_;
  std::string key = robot.empty() ? "(unnamed)" : robot;
  // A peer inventing robot ids must not grow these maps without bound either.
  if (robots_.size() >= kMaxRobotsTracked && robots_.count(key) == 0) key = "(others)";
  ++robots_[key][reason];
  std::string source = participant.empty() ? key : "participant " + participant;
  if (sources_.size() >= kMaxSourcesTracked && sources_.count(source) == 0) source = "(others)";
  SourceLog& log = sources_[source];
  if (now - log.period_start >= period_) {
    if (log.left_out > 0) {
      ++lines_logged_;
      spdlog::warn(
          "{}: refused {} more samples from {} in the last {} s without logging each", who_,
          log.left_out, source,
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
  ++lines_logged_;
  if (participant.empty()) {
    spdlog::warn("{}: refused from {} ({}): {}", who_, key, RefusalName(reason), detail);
  } else {
    spdlog::warn("{}: refused from {} of participant {} ({}): {}", who_, key, participant,
                 RefusalName(reason), detail);
  }
}

uint64_t RefusalLog::count(const std::string& robot, fusion::Refusal reason) const {
  const auto it = robots_.find(robot.empty() ? "(unnamed)" : robot);
  if (it == robots_.end()) return 0;
  const auto count = it->second.find(reason);
  return count == it->second.end() ? 0 : count->second;
}

std::map<std::string, std::map<fusion::Refusal, uint64_t>> RefusalLog::counts() const {
  return robots_;
}

}  // namespace fleetmap::server
