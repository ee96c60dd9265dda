#pragma once

// `fleetmap bench capacity`: how many robots one fleetmap-server core holds (issue 32). For each
// fleet size N, a fresh server pinned to one core, and a load generator in this process (on the
// other core) that plays N robots exploring: each robot its own id and status, 16 to a DDS
// participant (the server's limit per participant), publishing at --rate the tiles its exploration
// changed. The tile streams are recorded once before the sweep: a building (a simulated one, or a
// real SLAM map with --map) revealed column by column, vectorized into 10 m tiles at every step;
// eight robots share each building, each at its own phase, so their tiles overlap as a floor's
// robots' do. Measured per N, from --settle seconds after the join, on a reader of
// rt/fleetmap/fused_tiles: tile updates offered and
// fused per second, latency from the robot's tile stamp to the fused tile (p50, p99), the
// server's CPU (cores) and RSS, and how long until the server followed every robot (its log says
// it joined) and had fused each building's first tiles. Prints
// the largest N with p99 <= 50 ms; table, CSV and JSON. With --discovery server (or both), the
// fleet discovers through a Fast DDS discovery server (`fastdds discovery`, started per stage)
// instead of simple discovery, and the join's loopback traffic compares the two.

#include <CLI/CLI.hpp>

namespace fleetmap::bench {

void AddBenchCapacityCommand(CLI::App& app, int* exit_code);

}  // namespace fleetmap::bench
