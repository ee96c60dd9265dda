#include "server/server_role.hpp"

#include "common/transport/served_state.hpp"

namespace fleetmap::server {
namespace {

// Whether the server of (strength a, id a) outranks the one of (strength b, id b).
bool Ahead(int32_t strength_a, const std::string& id_a, int32_t strength_b,
           const std::string& id_b) {
  return strength_a != strength_b ? strength_a > strength_b : id_a < id_b;
}

}  // namespace

ServerRole::ServerRole(std::string own_id, int32_t strength, SteadyTime started, std::string shard)
    : own_id_(std::move(own_id)),
      strength_(strength),
      shard_(std::move(shard)),
      started_(started) {}

void ServerRole::Heard(const transport::FleetServerMessage& server, SteadyTime now) {
  if (server.server_id == own_id_ || server.shard != shard_) return;
  peers_[server.server_id] = Peer{server, now};
}

void ServerRole::Withdrew(const std::string& server_id) { peers_.erase(server_id); }

bool ServerRole::Decide(SteadyTime now) {
  std::erase_if(peers_, [&](const auto& entry) {
    return now - entry.second.heard > transport::kServerSilenceLimit;
  });
  Role role = Role::kListening;
  if (now - started_ >= transport::kServerSilenceLimit) {
    role = outranked_by() ? Role::kStandingBy : Role::kServing;
  }
  const bool changed = role != role_;
  role_ = role;
  return changed;
}

std::optional<transport::FleetServerMessage> ServerRole::outranked_by() const {
  std::optional<transport::FleetServerMessage> strongest;
  for (const auto& [id, peer] : peers_) {
    const transport::FleetServerMessage& server = peer.last;
    const bool ahead_of_me = Ahead(server.ownership_strength, id, strength_, own_id_);
    if (ahead_of_me && (!strongest || Ahead(server.ownership_strength, id,
                                            strongest->ownership_strength, strongest->server_id))) {
      strongest = server;
    }
  }
  return strongest;
}

std::vector<transport::FleetServerMessage> ServerRole::peers() const {
  std::vector<transport::FleetServerMessage> out;
  for (const auto& [id, peer] : peers_) out.push_back(peer.last);
  return out;
}

}  // namespace fleetmap::server
