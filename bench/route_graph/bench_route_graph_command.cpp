#include "bench/route_graph/bench_route_graph_command.hpp"

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <vector>

#include <opencv2/core/utility.hpp>

#include "bench/report/bench_command.hpp"
#include "bench/report/map_files.hpp"
#include "cli/inputs/command_inputs.hpp"
#include "cli/inputs/exit_codes.hpp"
#include "common/core/file_io.hpp"
#include "common/core/progress_line.hpp"

namespace fleetmap::bench {
int RunBenchRouteGraph(const BenchRouteGraphCommandOptions& options, std::ostream& out,
                       std::ostream& err) {
  auto fail = [&err](const std::string& message) {
    err << "fleetmap bench route-graph: " << message << "\n";
    return cli::kExitBadInput;
  };
  if (Status s = cli::CheckPositiveFinite("--radius", options.bench.robot_radius); !s.ok()) {
    return fail(s.message());
  }
  if (options.bench.runs < 1) return fail("--runs must be >= 1");
  if (options.bench.route_pairs < 1 || options.bench.cell_pairs < 1) {
    return fail("--route-pairs and --cell-pairs must be >= 1");
  }
  StatusOr<std::vector<std::string>> files = MapFilesIn(options.maps_dir);
  if (!files.ok()) return fail(files.status().message());
  // One thread: figures are per core, and OpenCV would otherwise use its pool.
  cv::setNumThreads(1);

  std::optional<ProgressLine> progress;
  if (options.progress) {
    progress.emplace(err, ProgressLineOptions{.terminal = options.err_is_terminal});
  }
  std::vector<RouteGraphBenchRow> rows;
  size_t skipped = 0;
  for (size_t i = 0; i < files->size(); ++i) {
    const std::string& file = (*files)[i];
    if (progress) {
      progress->Update("[route-graph] map " + std::to_string(i + 1) + " / " +
                       std::to_string(files->size()) + ": " + file);
    }
    StatusOr<RouteGraphBenchRow> row = MeasureRouteGraphBench(file, options.bench);
    if (!row.ok()) {
      if (progress) progress->Print(row.status().message() + " (skipped)");
      ++skipped;
      continue;
    }
    rows.push_back(std::move(row).value());
  }
  if (progress) progress->Finish("[route-graph] " + std::to_string(rows.size()) + " maps measured");
  if (rows.empty()) return fail(options.maps_dir + ": no map could be measured");
  const std::vector<RouteGraphTarget> targets = EvaluateRouteGraphTargets(rows);
  PrintRouteGraphBench(rows, targets, options.bench, out);
  if (!options.json_path.empty()) {
    const std::string json = RouteGraphBenchJson(rows, targets, options.bench).dump(2) + "\n";
    if (Status s = WriteFileAtomically(options.json_path, json); !s.ok()) return fail(s.message());
  }
  if (!options.csv_path.empty()) {
    if (Status s = WriteFileAtomically(options.csv_path, RouteGraphBenchCsv(rows)); !s.ok()) {
      return fail(s.message());
    }
  }
  out.flush();
  if (skipped > 0) {
    return fail(std::to_string(skipped) + " of " + std::to_string(files->size()) +
                " maps skipped, see above");
  }
  return out ? cli::kExitOk : cli::kExitBadInput;
}

void AddBenchRouteGraphCommand(CLI::App& app, int* exit_code) {
  auto options = std::make_shared<BenchRouteGraphCommandOptions>();
  CLI::App* cmd = BenchCommand(app)->add_subcommand(
      "route-graph",
      "The route graph against A* on the inflated grid, on every map of a directory");
  cmd->add_option("--maps", options->maps_dir, "Directory of map_server YAML files")->required();
  cmd->add_option("--radius", options->bench.robot_radius, "Robot radius, metres")
      ->capture_default_str();
  cmd->add_option("--route-pairs", options->bench.route_pairs, "Node pairs routed per map")
      ->capture_default_str();
  cmd->add_option("--cell-pairs", options->bench.cell_pairs,
                  "Grid-connected cell pairs checked per map")
      ->capture_default_str();
  cmd->add_option("--runs", options->bench.runs, "Timings are medians of N runs")
      ->capture_default_str();
  cmd->add_option("--seed", options->bench.seed, "Seed of the sampled pairs")
      ->capture_default_str();
  cmd->add_option("--json", options->json_path, "Write the figures as JSON here");
  cmd->add_option("--csv", options->csv_path, "Write the figures as CSV here");
  cmd->add_flag("!--no-progress", options->progress, "No progress lines on stderr");
  cmd->callback([options, exit_code]() {
    options->err_is_terminal = ProgressLine::StderrIsTerminal();
    *exit_code = RunBenchRouteGraph(*options, std::cout, std::cerr);
  });
}

}  // namespace fleetmap::bench
