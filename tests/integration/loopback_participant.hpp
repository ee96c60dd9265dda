#pragma once

// The integration tests' own DDS participant on a test's domain.

#include <memory>

#include "common/core/status.hpp"
#include "common/transport/participant.hpp"

namespace fleetmap::testing {

// Loopback only, and never delivering to itself inside the process, so that what the test reads
// came over the wire from the fleet's processes.
inline StatusOr<std::unique_ptr<transport::Participant>> LoopbackParticipant(int domain) {
  transport::ParticipantOptions options;
  options.domain_id = domain;
  options.localhost_only = true;
  options.intraprocess_delivery = false;
  return transport::Participant::Create(options);
}

}  // namespace fleetmap::testing
