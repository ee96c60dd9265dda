#pragma once

#include <chrono>
#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <utility>

namespace fleetmap::server {

// Why the server refused something a peer sent.
enum class Refusal {
  kMalformed,         // the sample failed its shape or content checks
  kBadRobotId,        // not a ROS 2 name token of at most 64 characters
  kTileOutOfRange,    // a tile key beyond the server's max_coordinate
  kBadTileSettings,   // tile size, epsilon or resolution outside what the server fuses
  kStampOutOfWindow,  // stamped too far ahead of the server's clock, or implausibly old
  kTileQuota,         // the robot already holds its maximum number of tiles
  kByteQuota,         // the robot sends more bytes per second than its quota
  kNotOwner,          // a sample for a robot id that another participant owns
  kNotItself,         // secured: a sample for a robot id other than its writer's identity
  kUnclaimed,         // tiles for a robot id no live status claims, held too long
};

const char* RefusalName(Refusal refusal);

// Counts every refusal per robot and reason, and logs them without letting a flood fill the log:
// per robot and `period`, each distinct message is logged once and at most kLinesPerPeriod
// messages in all; what is left out is summed up in one line when the next period begins. Not
// thread-safe: one owner thread.
class RefusalLog {
 public:
  explicit RefusalLog(std::string who, std::chrono::milliseconds period = std::chrono::seconds(10))
      : who_(std::move(who)), period_(period) {}

  // Counts a refusal; `robot` may be empty when the sample is too broken to name one.
  void Refuse(const std::string& robot, Refusal reason, const std::string& detail,
              std::chrono::steady_clock::time_point now = std::chrono::steady_clock::now());

  uint64_t count(const std::string& robot, Refusal reason) const;
  uint64_t total() const { return total_; }
  // Every count, by robot then reason.
  std::map<std::string, std::map<Refusal, uint64_t>> counts() const;

  static constexpr size_t kLinesPerPeriod = 20;

 private:
  struct RobotLog {
    std::map<Refusal, uint64_t> counts;
    std::chrono::steady_clock::time_point period_start{};
    std::set<std::string> logged;  // messages logged this period
    uint64_t left_out = 0;         // refusals not logged this period
  };
  static constexpr size_t kMaxRobotsTracked = 4096;  // beyond: counted under "(others)"

  std::string who_;
  std::chrono::milliseconds period_;
  std::map<std::string, RobotLog> robots_;
  uint64_t total_ = 0;
};

}  // namespace fleetmap::server
