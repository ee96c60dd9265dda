#pragma once

// `fleetmap sim --secure`: the same simulated fleet with and without DDS Security, side by side:
// how long robots take to join (the handshakes), the bytes on the wire and the tile latency.

#include <string>

#include "bench/fleet/fleet_sim.hpp"
#include "common/core/status.hpp"

namespace fleetmap::bench {

// The comparison as a table (text) and as JSON, written to `out_dir`/security.json; returns the
// table.
// `isolated`: each run had a network namespace of its own, so the loopback bytes are the fleet's
// alone (else the host's loopback: other traffic included).
StatusOr<std::string> WriteSecurityComparison(const FleetRunResult& secured,
                                              const FleetRunResult& plain, bool isolated,
                                              const std::string& out_dir);

}  // namespace fleetmap::bench
