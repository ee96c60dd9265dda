#pragma once

#include <CLI/CLI.hpp>

namespace fleetmap::bench {

// `fleetmap bench loss`: one simulated fleet per UDP loss rate, each in a network namespace of its
// own whose nftables rule drops that share of datagrams; a table of update latency, robots falsely
// reported lost and fused-map quality. Needs root, ip and nft.
void AddBenchLossCommand(CLI::App& app, int* exit_code);

}  // namespace fleetmap::bench
