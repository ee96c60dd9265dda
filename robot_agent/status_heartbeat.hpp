#pragma once

#include <chrono>
#include <mutex>

#include "common/core/robot_status.hpp"
#include "common/core/status.hpp"
#include "common/core/worker_thread.hpp"
#include "common/transport/robot_status_writer.hpp"

namespace fleetmap::agent {

// Publishes the robot's status every `period` from a thread of its own. The status is also the
// robot's liveliness (MANUAL_BY_TOPIC, a 2 s lease): it must not wait for the agent's main loop,
// which a burst of work (a big map to vectorize, a flood of other robots' ids to watch) can hold
// up long enough for the server to report a live robot lost. The loop hands over what changed
// (Update); the heartbeat stamps and numbers each sample it writes. A loop that has not handed
// anything over for `hung_after` has hung: the heartbeat then stops, and the server reports the
// robot lost, as a dead one.
class StatusHeartbeat {
 public:
  StatusHeartbeat(transport::RobotStatusWriter& writer, std::chrono::milliseconds period,
                  std::chrono::milliseconds hung_after = std::chrono::seconds(5))
      : writer_(writer), period_(period), hung_after_(hung_after), thread_(period) {}
  ~StatusHeartbeat() { Stop(); }
  StatusHeartbeat(const StatusHeartbeat&) = delete;
  StatusHeartbeat& operator=(const StatusHeartbeat&) = delete;

  // Writes `first` at once (an error says why the robot cannot join), then every period.
  Status Start(const RobotStatus& first);
  // What the next samples say (stamp and sequence number are the heartbeat's).
  void Update(const RobotStatus& status);
  // Writes the latest status now (e.g. the final byte accounting before leaving).
  Status WriteNow();
  // No status after this returns: the writer is the caller's again (to Leave()).
  void Stop() { thread_.Stop(); }

 private:
  Status Write();  // under write_mutex_

  transport::RobotStatusWriter& writer_;
  const std::chrono::milliseconds period_;
  const std::chrono::milliseconds hung_after_;
  RobotId robot_;  // set by Start(), for the log
  std::mutex mutex_;
  RobotStatus latest_;                                   // guarded by mutex_
  std::chrono::steady_clock::time_point last_update_{};  // guarded by mutex_
  bool hung_ = false;                                    // heartbeat thread only
  std::mutex write_mutex_;                               // one writer at a time
  std::chrono::steady_clock::time_point last_write_{};   // guarded by write_mutex_
  WorkerThread thread_;                                  // last: stops before the rest goes
};

}  // namespace fleetmap::agent
