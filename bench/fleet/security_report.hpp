#pragma once

// `fleetmap sim --secure`: the same simulated fleet with and without DDS Security, side by side:
// how long robots take to join (the handshakes), the bytes on the wire and the tile latency.

#include <string>

#include "bench/fleet/fleet_sim.hpp"
#include "common/core/status.hpp"

namespace fleetmap::bench {

// The comparison as a table (text) and as JSON, written to `out_dir`/security.json; returns the
// table.
StatusOr<std::string> WriteSecurityComparison(const FleetRunResult& secured,
                                              const FleetRunResult& plain,
                                              const std::string& out_dir);

}  // namespace fleetmap::bench
