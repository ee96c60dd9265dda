#pragma once

#include <map>
#include <mutex>
#include <string>

namespace fleetmap::server {

// Which agent speaks for which robot id: the DDS participant (the first 24 hex digits of a writer
// id) whose status claimed the id first. A second agent with the same id is a misconfiguration
// that must be reported, not merged. Thread-safe: the control thread claims, the fusion worker
// checks.
class RobotRegistry {
 public:
  enum class Claim { kNew, kSame, kClash };

  // Claims `robot` for the participant of `writer`.
  Claim ClaimRobot(const std::string& robot, const std::string& writer);
  // Frees the id when its robot left or was lost, so a restarted agent can take it.
  void Release(const std::string& robot);
  // Whether a sample from `writer` may speak for `robot` (true while nobody claimed it).
  bool MaySpeakFor(const std::string& robot, const std::string& writer) const;

  static std::string ParticipantOf(const std::string& writer) { return writer.substr(0, 24); }

 private:
  mutable std::mutex mutex_;
  std::map<std::string, std::string> participant_by_robot_;  // guarded by mutex_
};

}  // namespace fleetmap::server
