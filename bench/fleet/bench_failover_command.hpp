#pragma once

// `fleetmap bench failover`: what a hot standby is worth (issue 32, docs/standby.md). Per run, a
// primary server (ownership strength 100), a hot standby (50) and a reference server (10) that is
// never killed, then N simulated robots exploring, all real processes over DDS on loopback. After
// a warm-up the primary is killed (SIGKILL). Measured: how long after the kill a reader gets the
// standby's fused tiles, its rt/fleetmap/map and its robot frames; at the end, whether every fused
// tile the reader holds is the standby's last revision (nothing refused stays lost), and whether
// the standby's fused tiles are byte- and cell-identical to the reference server's (the same
// inputs, never killed), compared in their stores. Table, CSV and JSON.

#include <CLI/CLI.hpp>

namespace fleetmap::bench {

void AddBenchFailoverCommand(CLI::App& app, int* exit_code);

}  // namespace fleetmap::bench
