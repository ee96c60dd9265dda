#include "bench/report/bench_command.hpp"

#include <vector>

namespace fleetmap::bench {

CLI::App* BenchCommand(CLI::App& app) {
  const std::vector<CLI::App*> existing =
      app.get_subcommands([](CLI::App* sub) { return sub->get_name() == "bench"; });
  if (!existing.empty()) return existing.front();
  CLI::App* bench = app.add_subcommand("bench", "Benchmark drivers: print tables, write JSON/CSV");
  bench->require_subcommand(1);
  return bench;
}

}  // namespace fleetmap::bench
