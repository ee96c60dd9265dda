#pragma once

#include <array>
#include <chrono>
#include <memory>
#include <string>
#include <vector>

#include "common/core/status.hpp"
#include "common/core/wake_up.hpp"
#include "common/transport/keyed_state_topic.hpp"
#include "common/transport/participant.hpp"
#include "server/server_role.hpp"

namespace fleetmap::server {

// A fleetmap-server's presence among the fleet's servers (docs/standby.md): it says on
// rt/fleetmap/servers every transport::kServerHeartbeatPeriod that it is alive, follows the other
// servers there, and decides with ServerRole whether it serves. A server that starts serving
// writes its served state again (Participant::RepublishServedState) half a second later, when
// every reader has left the server before it, and once more a participant lease later, for
// readers that watch no liveliness and leave a dead server only when its participant expires.
// Call from one thread (the node's).
class FleetPresence {
 public:
  using SteadyTime = std::chrono::steady_clock::time_point;

  struct Identity {
    std::string server_id;  // the served participant's id (Participant::id())
    std::string name;       // for people
    int32_t strength = 0;
    std::string shard;               // a shard's server (docs/shards.md); empty: unsharded
    std::array<double, 4> region{};  // the shard's region: min x, min y, max x, max y
  };

  // Heartbeats go on `heartbeats` (a participant a flood of tiles cannot delay); the served state
  // is `served`'s.
  static StatusOr<std::unique_ptr<FleetPresence>> Create(transport::Participant& heartbeats,
                                                         transport::Participant& served,
                                                         Identity identity,
                                                         std::shared_ptr<WakeUp> wake_up);
  // Withdraws this server's instance: a standby takes over at once, not after the silence limit.
  ~FleetPresence();

  // Says it is alive (when due), follows the others, decides, writes the state again when due.
  // `robots`: how many robots it fuses. True when serving() may have changed.
  bool Tick(SteadyTime now, uint32_t robots);
  bool serving() const { return role_.serving(); }

 private:
  FleetPresence(transport::Participant& served, Identity identity, SteadyTime started);

  void SayAlive(SteadyTime now, uint32_t robots);
  void Follow(SteadyTime now);
  // Logs the new role; schedules the state written again when it serves.
  void RoleChanged(SteadyTime now);
  void RepublishWhenDue(SteadyTime now);

  transport::Participant& served_;
  Identity identity_;
  Timestamp started_;
  ServerRole role_;
  std::unique_ptr<transport::FleetServerWriter> writer_;
  std::unique_ptr<transport::FleetServerReader> reader_;
  SteadyTime next_heartbeat_{};
  std::vector<SteadyTime> republish_at_;
  bool write_failure_reported_ = false;
};

}  // namespace fleetmap::server
