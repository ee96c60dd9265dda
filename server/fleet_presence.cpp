#include "server/fleet_presence.hpp"

#include <spdlog/spdlog.h>

#include "common/transport/served_state.hpp"

namespace fleetmap::server {

using std::chrono::milliseconds;

StatusOr<std::unique_ptr<FleetPresence>> FleetPresence::Create(transport::Participant& heartbeats,
                                                               transport::Participant& served,
                                                               Identity identity,
                                                               std::shared_ptr<WakeUp> wake_up) {
  std::unique_ptr<FleetPresence> self(
      new FleetPresence(served, std::move(identity), std::chrono::steady_clock::now()));
  FLEETMAP_ASSIGN_OR_RETURN(self->writer_, transport::FleetServerWriter::Create(heartbeats));
  FLEETMAP_ASSIGN_OR_RETURN(self->reader_,
                            transport::FleetServerReader::Create(heartbeats, std::move(wake_up)));
  return self;
}

FleetPresence::FleetPresence(transport::Participant& served, Identity identity, SteadyTime started)
    : served_(served),
      identity_(std::move(identity)),
      started_(Clock::now()),
      role_(identity_.server_id, identity_.strength, started, identity_.shard) {}

FleetPresence::~FleetPresence() {
  if (!writer_) return;  // Create() failed before it could say anything
  transport::FleetServerMessage key;
  key.server_id = identity_.server_id;
  if (Status withdrawn = writer_->Dispose(key); !withdrawn.ok()) {
    spdlog::warn("server: {}", withdrawn.message());
  }
}

bool FleetPresence::Tick(SteadyTime now, uint32_t robots) {
  Follow(now);
  const bool changed = role_.Decide(now);
  if (changed) RoleChanged(now);
  if (changed || now >= next_heartbeat_) SayAlive(now, robots);
  RepublishWhenDue(now);
  return changed;
}

void FleetPresence::SayAlive(SteadyTime now, uint32_t robots) {
  next_heartbeat_ = now + transport::kServerHeartbeatPeriod;
  transport::FleetServerMessage message;
  message.server_id = identity_.server_id;
  message.name = identity_.name;
  message.ownership_strength = identity_.strength;
  message.serving = role_.serving();
  message.started = started_;
  message.stamp = Clock::now();
  message.robots = robots;
  message.shard = identity_.shard;
  message.region = identity_.region;
  if (StatusOr<size_t> written = writer_->Write(message); !written.ok()) {
    // Said once: a server that cannot say it is alive is taken for dead by its standbys.
    if (!write_failure_reported_) spdlog::error("server: {}", written.status().message());
    write_failure_reported_ = true;
  }
}

void FleetPresence::Follow(SteadyTime now) {
  for (transport::FleetServerEvent& event : reader_->Drain()) {
    switch (event.kind) {
      case transport::FleetServerEvent::Kind::kSample:
        role_.Heard(event.message, now);
        break;
      case transport::FleetServerEvent::Kind::kRemoved:
        role_.Withdrew(event.message.server_id);
        break;
      case transport::FleetServerEvent::Kind::kRejected:
        spdlog::warn("server: {}", event.error.message());
        break;
    }
  }
}

void FleetPresence::RoleChanged(SteadyTime now) {
  if (!role_.serving()) {
    republish_at_.clear();
    const auto serving = role_.outranked_by();
    spdlog::info(
        "server: standing by (ownership strength {}): server {} (strength {}) serves the fleet",
        identity_.strength, serving ? serving->name : std::string("?"),
        serving ? serving->ownership_strength : 0);
    return;
  }
  spdlog::info("server: serving the fleet (ownership strength {}, {} other server(s) live)",
               identity_.strength, role_.peers().size());
  const milliseconds settle{500};
  republish_at_ = {now + settle, now + served_.participant_lease() + settle};
}

void FleetPresence::RepublishWhenDue(SteadyTime now) {
  if (republish_at_.empty() || now < republish_at_.front()) return;
  republish_at_.erase(republish_at_.begin());
  const size_t instances = served_.RepublishServedState();
  spdlog::debug(
      "server: wrote its served state again ({} instances) for readers that followed "
      "another server",
      instances);
}

}  // namespace fleetmap::server
