#pragma once

// Which of the live fleetmap-servers serves the fleet (docs/standby.md). DDS-free: FleetPresence
// feeds it what rt/fleetmap/servers says.

#include <chrono>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "common/transport/state_messages.hpp"

namespace fleetmap::server {

// The strongest live server serves; of equal strengths the lowest server id, which is what DDS
// readers of the exclusive topics choose (a writer's GUID begins with its participant's id). A
// server not heard for transport::kServerSilenceLimit, or that withdrew, is gone. A server that
// starts listens that long before it serves, so that it stands by for a live stronger one
// instead of serving for a moment. Not thread-safe.
class ServerRole {
 public:
  using SteadyTime = std::chrono::steady_clock::time_point;

  // `shard`: a shard's servers rank among themselves only (docs/shards.md); empty: unsharded.
  ServerRole(std::string own_id, int32_t strength, SteadyTime started, std::string shard = {});

  // A server's sample, received at `now`; this server's own samples, and other shards', are
  // ignored.
  void Heard(const transport::FleetServerMessage& server, SteadyTime now);
  // The server withdrew (it stopped).
  void Withdrew(const std::string& server_id);
  enum class Role {
    kListening,   // started less than transport::kServerSilenceLimit ago
    kServing,     // no live server outranks it
    kStandingBy,  // a live server outranks it
  };

  // Decides at `now`; true when role() changed.
  bool Decide(SteadyTime now);

  Role role() const { return role_; }
  bool serving() const { return role_ == Role::kServing; }
  // The strongest live server that outranks this one, if any (the one that serves).
  std::optional<transport::FleetServerMessage> outranked_by() const;
  // The live servers heard from, this one left out.
  std::vector<transport::FleetServerMessage> peers() const;

 private:
  struct Peer {
    transport::FleetServerMessage last;
    SteadyTime heard;
  };

  std::string own_id_;
  int32_t strength_;
  std::string shard_;
  SteadyTime started_;
  Role role_ = Role::kListening;
  std::map<std::string, Peer> peers_;  // live ones, by server id
};

}  // namespace fleetmap::server
