#pragma once

#include <chrono>
#include <memory>
#include <vector>

#include "common/core/robot_status.hpp"
#include "common/core/status.hpp"
#include "common/core/wake_up.hpp"
#include "common/transport/participant.hpp"

namespace fleetmap::transport {

class ReaderEndpoint;

// How long a robot's status writer may stay silent before the robot is reported lost: four
// status periods, so a live robot survives three lost statuses in a row plus their repairs on a
// lossy link, and a dead one is still reported within about 2 s (docs/fleet.md).
inline constexpr std::chrono::milliseconds kRobotLivelinessLease{2000};

// What the fleet says about its robots.
struct RobotEvent {
  enum class Kind {
    kStatus,    // a status sample: the robot is alive (joined, or still there)
    kLeft,      // the robot disposed its status: it left on purpose
    kLost,      // its writer's liveliness lapsed or it vanished: it died or was cut off
    kRejected,  // a malformed status sample; `error` says what was wrong
  };
  Kind kind = Kind::kStatus;
  RobotId robot;
  RobotStatus status;  // for kStatus
  Status error;        // for kRejected
  // The DDS writer that sent the status, the disposal or whose liveliness lapsed: only the
  // writer that owns a robot id may end its robot (two per robot id: a clash or a hijack).
  std::string writer;

  static RobotEvent Alive(RobotStatus status);
  static RobotEvent Gone(Kind kind, RobotId robot, std::string writer);
  static RobotEvent Rejected(Status error);
};

const char* RobotEventKindName(RobotEvent::Kind kind);

// The server's reader of rt/fleetmap/robot_status. The DDS listener only drains samples into a
// queue and wakes the worker; Drain() hands them over. Drain() may be called from one thread.
class RobotStatusReader {
 public:
  static StatusOr<std::unique_ptr<RobotStatusReader>> Create(
      Participant& participant, std::shared_ptr<WakeUp> wake_up = nullptr);
  // A reader of one robot id's statuses only (an agent watching for another claim of its id):
  // the writers send it no other robot's (a DDS content filter).
  static StatusOr<std::unique_ptr<RobotStatusReader>> CreateForRobot(
      Participant& participant, const RobotId& robot, std::shared_ptr<WakeUp> wake_up = nullptr);
  ~RobotStatusReader();

  std::vector<RobotEvent> Drain();

 private:
  class Listener;
  RobotStatusReader() = default;

  std::unique_ptr<Listener> listener_;
  std::unique_ptr<ReaderEndpoint> endpoint_;
};

}  // namespace fleetmap::transport
