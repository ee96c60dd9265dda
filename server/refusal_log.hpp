#pragma once

#include <chrono>
#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <utility>

#include "common/fusion/refusal.hpp"

namespace fleetmap::server {

// Counts every refusal per robot and reason, and logs them without letting a flood fill the log:
// per source and `period`, each distinct message is logged once and at most kLinesPerPeriod
// messages in all; what is left out is summed up in one line when the next period begins. The
// source is the DDS participant that sent the sample where it is known (ids are free to invent:
// 2,000 ids of one participant log as much as one), else the robot. Not thread-safe: one owner
// thread.
class RefusalLog {
 public:
  explicit RefusalLog(std::string who, std::chrono::milliseconds period = std::chrono::seconds(10))
      : who_(std::move(who)), period_(period) {}

  // Counts a refusal; `robot` may be empty when the sample is too broken to name one.
  void Refuse(const std::string& robot, fusion::Refusal reason, const std::string& detail,
              std::chrono::steady_clock::time_point now = std::chrono::steady_clock::now());
  // The same, rate-limited per `participant` (empty: per robot).
  void RefuseFrom(const std::string& participant, const std::string& robot, fusion::Refusal reason,
                  const std::string& detail,
                  std::chrono::steady_clock::time_point now = std::chrono::steady_clock::now());

  uint64_t count(const std::string& robot, fusion::Refusal reason) const;
  uint64_t total() const { return total_; }
  // Lines written to the log so far (refusals and summaries).
  uint64_t lines_logged() const { return lines_logged_; }
  // Every count, by robot then reason.
  std::map<std::string, std::map<fusion::Refusal, uint64_t>> counts() const;

  static constexpr size_t kLinesPerPeriod = 20;

 private:
  struct SourceLog {
    std::chrono::steady_clock::time_point period_start{};
    std::set<std::string> logged;  // messages logged this period
    uint64_t left_out = 0;         // refusals not logged this period
  };
  static constexpr size_t kMaxRobotsTracked = 4096;   // beyond: counted under "(others)"
  static constexpr size_t kMaxSourcesTracked = 1024;  // beyond: logged as "(others)"

  std::string who_;
  std::chrono::milliseconds period_;
  std::map<std::string, std::map<fusion::Refusal, uint64_t>> robots_;  // counts by robot
  std::map<std::string, SourceLog> sources_;
  uint64_t total_ = 0;
  uint64_t lines_logged_ = 0;
};

}  // namespace fleetmap::server
