#pragma once

// `fleetmap bench <driver>`: the parent of the benchmark drivers (they print tables; they are not
// tests). Each driver registers itself under it with BenchCommand(app)->add_subcommand(...).

#include <CLI/CLI.hpp>

namespace fleetmap::bench {

// The `bench` subcommand of `app`, created on first use, so drivers can register in any order.
CLI::App* BenchCommand(CLI::App& app);

}  // namespace fleetmap::bench
